// Decodes raw CDR samples (hex, as tests/record/tap.py took them off the wire) with a channel's
// advertised omgidl schema, through @foxglove/omgidl-parser + @foxglove/omgidl-serialization.
// The file holds {"schema": {schemaName, ...advertised channel}, "hex": [...]}; prints a JSON list.
"use strict";
const fs = require("fs");
const { parseIDL } = require("@foxglove/omgidl-parser");
const { MessageReader } = require("@foxglove/omgidl-serialization");

const { schema, hex } = JSON.parse(fs.readFileSync(process.argv[2], "utf-8"));
const reader = new MessageReader(schema.schemaName, parseIDL(schema.schema));
const out = hex.map((h) => reader.readMessage(Uint8Array.from(Buffer.from(h, "hex"))));
console.log(JSON.stringify(out, (k, v) =>
  typeof v === "bigint" ? v.toString() : ArrayBuffer.isView(v) ? Array.from(v) : v));
