// An independent reading of a vkfuse recording (FILE.mcap): @mcap/core reads
// it indexed and as a stream, CRCs checked, chunks decompressed by
// @mcap/support's zstd and lz4; each message is decoded with Foxglove's CDR
// reader (@foxglove/rosmsg2-serialization) from the ros2msg schema the file
// carries (parsed by @foxglove/rosmsg), not from vkfuse's code. Prints one
// line per message, sorted:
//   frame SERIAL PRESSED BACKGROUND CYCLE INDEX TIMESTAMP LEVELS WxH ENCODING STEP BYTESUM
//   miss SERIAL CYCLE STATUS ERROR
//   rig SERIAL:TOKEN:MODEL:WxH:LED_MODEL:CHANNELS:MAX,... SETTINGS METHOD fused=F frames=F background_frames=N
// then "messages N chunks C compression NAME". Exits non-zero with the
// reason on anything it refuses, or when the two readings disagree.
//
//   node read_recording.mjs FILE
import { open, readFile } from "node:fs/promises";
import { createHash } from "node:crypto";
import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { FileHandleReadable } from "@mcap/nodejs";
import { loadDecompressHandlers } from "@mcap/support";
import { parse } from "@foxglove/rosmsg";
import { MessageReader } from "@foxglove/rosmsg2-serialization";

const file = process.argv[2];
const decompressHandlers = await loadDecompressHandlers();
const text = new TextDecoder();

const readers = new Map();  // schema id -> MessageReader
const decoder = (schema) => {
  if (!readers.has(schema.id)) {
    if (schema.encoding !== "ros2msg") throw new Error(`${file}: schema ${schema.name} is ${schema.encoding}`);
    readers.set(schema.id, new MessageReader(parse(text.decode(schema.data), { ros2: true })));
  }
  return readers.get(schema.id);
};

const line = (channel, schema, m) => {
  if (channel.messageEncoding !== "cdr") throw new Error(`${file}: ${channel.topic} is ${channel.messageEncoding}`);
  const msg = decoder(schema).readMessage(m.data);
  if (schema.name === "vkfuse_msgs/msg/RecordedFrame") {
    const img = msg.frame.image;
    const sha = createHash("sha1").update(img.data).digest("hex");
    const stamp = BigInt(img.header.stamp.sec) * 1000000000n + BigInt(img.header.stamp.nanosec);
    if (stamp !== m.logTime) throw new Error(`${file}: ${channel.topic} ${m.sequence}: stamp ${stamp} but log time ${m.logTime}`);
    return `frame ${img.header.frame_id} ${msg.pressed} ${msg.background} ${msg.cycle} ${msg.frame.index} ` +
           `${msg.frame.timestamp} ${Array.from(msg.frame.setting.levels).join(",")} ${img.width}x${img.height} ` +
           `${img.encoding} ${img.step} ${sha}`;
  }
  if (schema.name === "vkfuse_msgs/msg/RigDescription") {
    const stamp = BigInt(msg.header.stamp.sec) * 1000000000n + BigInt(msg.header.stamp.nanosec);
    if (stamp !== m.logTime) throw new Error(`${file}: ${channel.topic}: stamp ${stamp} but log time ${m.logTime}`);
    const sensors = msg.sensors.map((s) => [s.serial, s.token, s.model.replaceAll(" ", "_"), `${s.width}x${s.height}`,
                                            s.led_model, s.led_channels.join("/"), s.led_max_level].join(":"));
    const settings = msg.settings.map((s) => Array.from(s.levels).join(",")).join("+");
    return `rig ${sensors.join(",")} ${settings || "-"} ${msg.method || "-"} fused=${msg.fused} frames=${msg.frames} ` +
           `background_frames=${msg.background_frames}`;
  }
  if (schema.name === "vkfuse_msgs/msg/FusionMetrics")
    return `miss ${msg.serial} ${msg.cycle} ${msg.status} ${JSON.stringify(msg.error)}`;
  throw new Error(`${file}: unexpected schema ${schema.name} on ${channel.topic}`);
};

const handle = await open(file, "r");
const indexed = await McapIndexedReader.Initialize({ readable: new FileHandleReadable(handle), decompressHandlers });
if (!indexed.statistics) throw new Error(`${file}: no Statistics record`);
const fromIndex = [];
for await (const m of indexed.readMessages({ validateCrcs: true })) {
  const channel = indexed.channelsById.get(m.channelId);
  fromIndex.push(line(channel, indexed.schemasById.get(channel.schemaId), m));
}
const metadata = [];
for await (const r of indexed.readMetadata({ name: "vkfuse.dataset" })) metadata.push(r);
if (metadata.length !== 1) throw new Error(`${file}: ${metadata.length} vkfuse.dataset metadata records`);
const manifest = JSON.parse(metadata[0].metadata.get("manifest"));
await handle.close();

const stream = new McapStreamReader({ validateCrcs: true, decompressHandlers });
stream.append(await readFile(file));
const channels = new Map(), schemas = new Map();
const fromStream = [];
const compressions = new Set();
let record, sawFooter = false;
while ((record = stream.nextRecord())) {
  if (record.type === "Schema") schemas.set(record.id, record);
  if (record.type === "Channel") channels.set(record.id, record);
  if (record.type === "Message") {
    const channel = channels.get(record.channelId);
    fromStream.push(line(channel, schemas.get(channel.schemaId), record));
  }
  if (record.type === "Footer") sawFooter = true;
}
if (!stream.done() || !sawFooter) throw new Error(`${file}: the stream reader did not reach the footer`);
for (const c of indexed.chunkIndexes) compressions.add(c.compression || "none");
fromIndex.sort();
fromStream.sort();
if (fromIndex.join("\n") !== fromStream.join("\n")) throw new Error(`${file}: indexed and streamed readings differ`);
if (BigInt(fromIndex.length) !== indexed.statistics.messageCount) throw new Error(`${file}: statistics count other messages`);
for (const l of fromIndex) console.log(l);
console.log(`sensors ${manifest.sensors.map((s) => s.serial).join(",")} source ${JSON.stringify(manifest.source)}`);
console.log(`messages ${fromIndex.length} chunks ${indexed.chunkIndexes.length} compression ${[...compressions].join(",")}`);
