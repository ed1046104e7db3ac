// Reads a morsec recording with Foxglove's own MCAP reader (@mcap/core, as Foxglove opens files) and prints, as
// one JSON object: the header, every channel with its schema, the message count, the morsec metadata's keys, and
// the first messages of a JSON channel decoded (their log times as strings: they are 64-bit).
//
//     node tests/node/read_mcap.mjs run.mcap robot.pose [count]
import { open } from "node:fs/promises";
import { McapIndexedReader } from "@mcap/core";
import { FileHandleReadable } from "@mcap/nodejs";
import { loadDecompressHandlers } from "@mcap/support";

const [path, topic, count = "3"] = process.argv.slice(2);
const handle = await open(path, "r");
try {
  const reader = await McapIndexedReader.Initialize({
    readable: new FileHandleReadable(handle),
    decompressHandlers: await loadDecompressHandlers(),
  });
  const channels = [...reader.channelsById.values()].map((channel) => {
    const schema = reader.schemasById.get(channel.schemaId);
    return {
      topic: channel.topic,
      messageEncoding: channel.messageEncoding,
      schemaName: schema?.name,
      schemaEncoding: schema?.encoding,
      schema: schema ? new TextDecoder().decode(schema.data) : null,
    };
  });
  const metadata = {};
  for await (const record of reader.readMetadata({ name: "morsec" })) {
    metadata[record.name] = [...record.metadata.keys()];
  }
  const messages = [];
  for await (const message of reader.readMessages({ topics: [topic] })) {
    if (messages.length >= Number(count)) break;
    messages.push({
      logTime: message.logTime.toString(),
      sequence: message.sequence,
      data: JSON.parse(new TextDecoder().decode(message.data)),
    });
  }
  console.log(JSON.stringify({
    profile: reader.header.profile,
    library: reader.header.library,
    channels,
    messageCount: reader.statistics?.messageCount.toString(),
    metadata,
    messages,
  }));
} finally {
  await handle.close();
}
