// Foxglove's own WebSocket client (@foxglove/ws-protocol) watching a `morsec run --foxglove`, for the tests:
//
//     node tests/foxglove/watch.mjs ws://127.0.0.1:8765 [--seconds 30] [--until-stdin-closes] [--count]
//
// It connects with the subprotocol foxglove-sdk's server speaks (foxglove.sdk.v1), subscribes to every channel
// advertised, decodes each message with its channel's schema as the Foxglove app does (protobuf: the channel's
// FileDescriptorSet through protobufjs; json: the text) and prints one JSON line per event:
//
//     {"event": "open", "protocol": ...}        {"event": "serverInfo", ...}
//     {"event": "advertise", "channel": {id, topic, encoding, schemaName, schemaEncoding, schema}}
//     {"event": "message", "topic": ..., "logTime": "<ns>", "message": {...}}    bytes as {"bytes": n, "head": base64}
//     {"event": "time", "timestamp": "<ns>"}      {"event": "close"}
//
// It stops after --seconds (60), or when its standard input closes if asked to. With --count (the benchmark's
// client) it decodes nothing and prints, when it stops, one line {"event": "count", "messages": {topic: n}}.
import wsProtocol from "@foxglove/ws-protocol";
import protobuf from "protobufjs";
import descriptor from "protobufjs/ext/descriptor/index.js";
import WebSocket from "ws";

const { FoxgloveClient } = wsProtocol; // a CommonJS package
const SUBPROTOCOL = "foxglove.sdk.v1";
const HEAD_BYTES = 96;

const url = process.argv[2];
const secondsAt = process.argv.indexOf("--seconds");
const seconds = secondsAt > 0 ? Number(process.argv[secondsAt + 1]) : 60;

function emit(event) {
  process.stdout.write(JSON.stringify(event, (_key, value) => (typeof value === "bigint" ? value.toString() : value)) + "\n");
}

function plain(value) {
  if (value instanceof Uint8Array) {
    return { bytes: value.length, head: Buffer.from(value.subarray(0, HEAD_BYTES)).toString("base64") };
  }
  if (Array.isArray(value)) return value.map(plain);
  if (value !== null && typeof value === "object") {
    return Object.fromEntries(Object.entries(value).map(([k, v]) => [k, plain(v)]));
  }
  return value;
}

function decoder(channel) {
  if (channel.encoding === "json") {
    const text = new TextDecoder();
    return (data) => JSON.parse(text.decode(data));
  }
  if (channel.encoding === "protobuf") {
    const set = descriptor.FileDescriptorSet.decode(Buffer.from(channel.schema, "base64"));
    const type = protobuf.Root.fromDescriptor(set).lookupType(channel.schemaName);
    return (data) => plain(type.toObject(type.decode(data), { longs: Number, enums: String, defaults: true }));
  }
  throw new Error(`no decoder for encoding ${channel.encoding} (${channel.topic})`);
}

const counting = process.argv.includes("--count");
const counts = {};

const ws = new WebSocket(url, [SUBPROTOCOL]);
const client = new FoxgloveClient({ ws });
const subscriptions = new Map(); // subscription id -> {topic, decode (unless counting)}

client.on("open", () => emit({ event: "open", protocol: ws.protocol }));
client.on("serverInfo", (info) => emit({ event: "serverInfo", ...info }));
client.on("error", (error) => emit({ event: "error", error: String(error) }));
client.on("close", () => {
  if (counting) emit({ event: "count", messages: counts });
  emit({ event: "close" });
  process.exit(0);
});
client.on("time", ({ timestamp }) => counting || emit({ event: "time", timestamp }));
client.on("advertise", (channels) => {
  for (const channel of channels) {
    if (counting) {
      subscriptions.set(client.subscribe(channel.id), { topic: channel.topic });
      continue;
    }
    const schema = channel.schemaEncoding === "jsonschema" ? JSON.parse(channel.schema) : channel.schema.length;
    emit({ event: "advertise", channel: { ...channel, schema } });
    try {
      subscriptions.set(client.subscribe(channel.id), { topic: channel.topic, decode: decoder(channel) });
    } catch (error) {
      emit({ event: "error", topic: channel.topic, error: String(error) });
    }
  }
});
client.on("message", ({ subscriptionId, timestamp, data }) => {
  const subscription = subscriptions.get(subscriptionId);
  if (counting) {
    counts[subscription.topic] = (counts[subscription.topic] ?? 0) + 1;
    return;
  }
  const bytes = new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
  try {
    emit({ event: "message", topic: subscription.topic, logTime: timestamp, message: subscription.decode(bytes) });
  } catch (error) {
    emit({ event: "error", topic: subscription.topic, error: String(error) });
  }
});

function stop() {
  ws.close();
  setTimeout(() => process.exit(0), 500);
}
if (process.argv.includes("--until-stdin-closes")) {
  process.stdin.on("end", stop);
  process.stdin.resume();
}
setTimeout(stop, seconds * 1000);
