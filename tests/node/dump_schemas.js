// Prints the JSON Schemas @foxglove/schemas publishes (its jsonschema export) for the names given
// ("foxglove.LocationFix" ...), as one JSON object {name: schema}; an unknown name fails.
"use strict";
const { published } = require("./foxglove_schemas");
const out = {};
for (const name of process.argv.slice(2)) {
  if (!published.has(name)) throw new Error(`@foxglove/schemas publishes no ${name}`);
  out[name] = published.get(name);
}
console.log(JSON.stringify(out));
