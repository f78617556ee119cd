// A Foxglove WebSocket client built on Foxglove's own @foxglove/ws-protocol (with the `ws`
// package as its socket): connects, subscribes to every channel advertised (then and later),
// and decodes each message with its channel's advertised schema: omgidl/cdr through
// @foxglove/omgidl-parser + @foxglove/omgidl-serialization, jsonschema/json through JSON.parse,
// validated against @foxglove/schemas (ajv).
//
//   node tests/node/ws_client.js URL SECONDS
//
// Prints one JSON line: {"subprotocol": ..., "server": name, "channels": [{id, topic, encoding,
// schemaName, schemaEncoding, schema}], "messages": {topic: [{"timestamp": ns, "message": decoded}]},
// "failed": [[topic, error]], "invalid": [[topic, schema, errors]], "closed": [code, reason] | null}.
"use strict";
const WebSocket = require("ws");
const { FoxgloveClient } = require("@foxglove/ws-protocol");
const { parseIDL } = require("@foxglove/omgidl-parser");
const { MessageReader } = require("@foxglove/omgidl-serialization");
const { validator } = require("./foxglove_schemas");

const [url, seconds] = process.argv.slice(2);
const ws = new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
const client = new FoxgloveClient({ ws });
const out = { subprotocol: null, server: null, channels: [], messages: {}, failed: [], invalid: [], closed: null };
const channels = new Map(), subs = new Map(), decoders = new Map();

function decoder(ch) {
  if (!decoders.has(ch.id)) {
    let d;
    if (ch.encoding === "cdr" && ch.schemaEncoding === "omgidl") {
      const reader = new MessageReader(ch.schemaName, parseIDL(ch.schema));
      d = (data) => reader.readMessage(data);
    } else if (ch.encoding === "json" && ch.schemaEncoding === "jsonschema") {
      const validate = validator(ch.schemaName);
      const text = new TextDecoder("utf-8", { fatal: true });
      d = (data) => {
        const msg = JSON.parse(text.decode(data));
        if (!validate(msg)) out.invalid.push([ch.topic, ch.schemaName, validate.errors]);
        return msg;
      };
    } else {
      d = () => { throw new Error(`unexpected encodings ${ch.encoding}/${ch.schemaEncoding}`); };
    }
    decoders.set(ch.id, d);
  }
  return decoders.get(ch.id);
}

client.on("open", () => { out.subprotocol = ws.protocol; });
client.on("serverInfo", (info) => { out.server = info.name; });
client.on("advertise", (list) => {
  for (const ch of list) {
    channels.set(ch.id, ch);
    out.channels.push({ id: ch.id, topic: ch.topic, encoding: ch.encoding, schemaName: ch.schemaName,
                        schemaEncoding: ch.schemaEncoding, schema: ch.schema });
    subs.set(client.subscribe(ch.id), ch);
  }
});
client.on("message", ({ subscriptionId, timestamp, data }) => {
  const ch = subs.get(subscriptionId);
  try {
    const msg = decoder(ch)(new Uint8Array(data.buffer, data.byteOffset, data.byteLength));
    (out.messages[ch.topic] ??= []).push({ timestamp: timestamp.toString(), message: msg });
  } catch (e) {
    out.failed.push([ch ? ch.topic : String(subscriptionId), String(e).slice(0, 300)]);
  }
});
client.on("error", (e) => { out.failed.push(["", String(e && e.message ? e.message : e)]); });
client.on("close", (e) => { out.closed = [e.code, String(e.reason)]; });

setTimeout(() => {
  client.close();
  const text = JSON.stringify(out, (k, v) =>
    typeof v === "bigint" ? v.toString() : ArrayBuffer.isView(v) ? Array.from(v) : v);
  process.stdout.write(text + "\n", () => process.exit(0));  // all of it through a pipe, then exit
}, Number(seconds) * 1000);
