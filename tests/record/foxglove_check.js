// Foxglove's own libraries read a recording (uncompressed chunks): every omgidl schema parsed
// by @foxglove/omgidl-parser, every cdr message decoded by @foxglove/omgidl-serialization.
// Prints one JSON line: {"decoded": N, "failed": [[topic, schema, error], ...], "schemas": N,
// "sample": {topic: first decoded message}}. Used by tests/record/test_record.py when the
// packages resolve (NODE_PATH); docs/record.md says how to install them.
const fs = require("fs");
const { McapStreamReader } = require("@mcap/core");
const { parseIDL } = require("@foxglove/omgidl-parser");
const { MessageReader } = require("@foxglove/omgidl-serialization");

const reader = new McapStreamReader();
reader.append(fs.readFileSync(process.argv[2]));
const schemas = new Map(), channels = new Map(), readers = new Map();
const out = { decoded: 0, failed: [], schemas: 0, sample: {} };
for (let rec; (rec = reader.nextRecord()); ) {
  if (rec.type === "Schema") schemas.set(rec.id, rec);
  else if (rec.type === "Channel") channels.set(rec.id, rec);
  else if (rec.type === "Message") {
    const ch = channels.get(rec.channelId), s = schemas.get(ch.schemaId);
    try {
      if (!readers.has(s.id)) readers.set(s.id, new MessageReader(s.name, parseIDL(new TextDecoder().decode(s.data))));
      const msg = readers.get(s.id).readMessage(rec.data);
      if (!(ch.topic in out.sample)) out.sample[ch.topic] = msg;
      out.decoded++;
    } catch (e) {
      out.failed.push([ch.topic, s.name, String(e).slice(0, 200)]);
    }
  }
}
out.schemas = schemas.size;
console.log(JSON.stringify(out, (k, v) => (typeof v === "bigint" ? v.toString() : v)));
