// Foxglove's own libraries read rapidgen recordings as written (zstd chunks): @mcap/core's
// stream reader with @mcap/support's decompress handlers; every omgidl schema parsed by
// @foxglove/omgidl-parser and every cdr message decoded by @foxglove/omgidl-serialization;
// every json message of a derived channel (`rapidgen record --foxglove`) parsed and validated
// with ajv against the JSON Schema that @foxglove/schemas publishes for its schema name.
//
//   node tests/node/read_mcap.js [--all] FILE.mcap [FILE.mcap ...]
//
// Prints one JSON line: {"decoded": N, "failed": [[file, topic, schema, error], ...],
// "schemas": N, "compression": [names of the chunks' compressions], "sample": {topic: first
// decoded message}, "derived": {topic: [{"log_time": ns, "schema": name, "message": msg}]},
// "invalid": [[topic, schema, ajv errors], ...]}; with --all also "messages": {topic: [every
// decoded RAPID message, in file order]} (byte arrays as lists of numbers). Used by tests/record/test_record.py and
// tests/record/test_foxglove.py; scripts/setup.sh installs the packages (tests/node).
"use strict";
const fs = require("fs");
const { McapStreamReader } = require("@mcap/core");
const { loadDecompressHandlers } = require("@mcap/support");
const { parseIDL } = require("@foxglove/omgidl-parser");
const { MessageReader } = require("@foxglove/omgidl-serialization");
const { validator } = require("./foxglove_schemas");

async function main() {
  const decompressHandlers = await loadDecompressHandlers();
  const out = { decoded: 0, failed: [], schemas: 0, compression: [], sample: {}, derived: {}, invalid: [] };
  const compression = new Set();
  let schemaCount = 0;
  const args = process.argv.slice(2);
  const all = args[0] === "--all";
  if (all) out.messages = {};
  for (const file of all ? args.slice(1) : args) {
    const reader = new McapStreamReader({ includeChunks: true, decompressHandlers });
    reader.append(fs.readFileSync(file));
    const schemas = new Map(), channels = new Map(), readers = new Map();
    for (let rec; (rec = reader.nextRecord()); ) {
      if (rec.type === "Chunk") compression.add(rec.compression);
      else if (rec.type === "Schema") schemas.set(rec.id, rec);
      else if (rec.type === "Channel") channels.set(rec.id, rec);
      else if (rec.type === "Message") {
        const ch = channels.get(rec.channelId), s = schemas.get(ch.schemaId);
        try {
          let msg;
          if (ch.messageEncoding === "cdr" && s.encoding === "omgidl") {
            if (!readers.has(s.id)) readers.set(s.id, new MessageReader(s.name, parseIDL(new TextDecoder().decode(s.data))));
            msg = readers.get(s.id).readMessage(rec.data);
            if (all) (out.messages[ch.topic] ??= []).push(msg);
          } else if (ch.messageEncoding === "json" && s.encoding === "jsonschema") {
            msg = JSON.parse(new TextDecoder("utf-8", { fatal: true }).decode(rec.data));
            const validate = validator(s.name);
            if (!validate(msg)) out.invalid.push([ch.topic, s.name, validate.errors]);
            (out.derived[ch.topic] ??= []).push({ log_time: rec.logTime.toString(), schema: s.name, message: msg });
          } else {
            throw new Error(`unexpected encodings ${ch.messageEncoding}/${s.encoding}`);
          }
          if (!(ch.topic in out.sample)) out.sample[ch.topic] = msg;
          out.decoded++;
        } catch (e) {
          out.failed.push([file, ch.topic, s.name, String(e).slice(0, 300)]);
        }
      }
    }
    if (!reader.done()) out.failed.push([file, "", "", "the file ended before its footer"]);
    schemaCount += schemas.size;
  }
  out.schemas = schemaCount;
  out.compression = [...compression].sort();
  console.log(JSON.stringify(out, (k, v) =>
    typeof v === "bigint" ? v.toString() : ArrayBuffer.isView(v) ? Array.from(v) : v));
}

main().catch((e) => {
  console.error(String(e && e.stack ? e.stack : e));
  process.exit(1);
});
