// The JSON Schemas that Foxglove publishes for its well-known messages (@foxglove/schemas'
// jsonschema export), compiled by ajv: validator("foxglove.LocationFix") is a function that
// checks a parsed message (its .errors say what failed). An unknown name throws.
"use strict";
const Ajv = require("ajv");
const published = require("@foxglove/schemas/jsonschema");

// strict: false: the published schemas use keywords ajv does not know (contentEncoding, $comment
// is fine); every keyword it does know is enforced (types, required, minItems, const of enums...)
const ajv = new Ajv({ strict: false, allErrors: true });
const byTitle = new Map();
for (const schema of Object.values(published)) {
  if (schema && typeof schema.title === "string") byTitle.set(schema.title, schema);
}
const compiled = new Map();

function validator(name) {
  if (!compiled.has(name)) {
    const schema = byTitle.get(name);
    if (!schema) throw new Error(`@foxglove/schemas publishes no JSON Schema titled ${name}`);
    compiled.set(name, ajv.compile(schema));
  }
  return compiled.get(name);
}

module.exports = { validator, published: byTitle };
