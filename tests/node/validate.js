// Validates messages against @foxglove/schemas' JSON Schemas: the file holds [[schema name,
// message], ...]; prints {"valid": N, "invalid": [[index, schema, ajv errors], ...]}.
"use strict";
const fs = require("fs");
const { validator } = require("./foxglove_schemas");
const out = { valid: 0, invalid: [] };
JSON.parse(fs.readFileSync(process.argv[2], "utf-8")).forEach(([name, msg], i) => {
  const v = validator(name);
  if (v(msg)) out.valid++;
  else out.invalid.push([i, name, v.errors]);
});
console.log(JSON.stringify(out));
