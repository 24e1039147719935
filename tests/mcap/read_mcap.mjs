// The independent reader vkfuse's MCAP files are checked with: @mcap/core
// (the MCAP project's own TypeScript library, pinned in package-lock.json),
// reading FILE twice - indexed (summary, chunk indexes, message indexes,
// CRCs) and as a stream (every record in order, CRCs) - and printing each
// message as "topic sequence log_time publish_time length bytesum", in log
// time order, then one line of statistics. Exits non-zero with the reader's
// error on anything it refuses, or when the two readings disagree.
//
//   node read_mcap.mjs FILE
import { open, readFile } from "node:fs/promises";
import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { FileHandleReadable } from "@mcap/nodejs";
import { loadDecompressHandlers } from "@mcap/support";

const file = process.argv[2];
const decompressHandlers = await loadDecompressHandlers();
const line = (channels, m) => {
  let sum = 0;
  for (const b of m.data) sum = (sum + b) >>> 0;
  return `${channels.get(m.channelId).topic} ${m.sequence} ${m.logTime} ${m.publishTime} ${m.data.length} ${sum}`;
};

const handle = await open(file, "r");
const indexed = await McapIndexedReader.Initialize({ readable: new FileHandleReadable(handle), decompressHandlers });
if (!indexed.statistics) throw new Error(`${file}: no Statistics record`);
const fromIndex = [];
for await (const m of indexed.readMessages({ validateCrcs: true })) fromIndex.push(line(indexed.channelsById, m));
await handle.close();

const stream = new McapStreamReader({ validateCrcs: true, decompressHandlers });
stream.append(await readFile(file));
const channels = new Map();
const fromStream = [];
let record, sawFooter = false;
while ((record = stream.nextRecord())) {
  if (record.type === "Channel") channels.set(record.id, record);
  if (record.type === "Message") fromStream.push(line(channels, record));
  if (record.type === "Footer") sawFooter = true;
}
if (!stream.done() || !sawFooter) throw new Error(`${file}: the stream reader did not reach the footer`);
fromStream.sort((a, b) => {
  const ta = BigInt(a.split(" ")[2]), tb = BigInt(b.split(" ")[2]);
  return ta < tb ? -1 : ta > tb ? 1 : 0;
});
if (fromIndex.join("\n") !== fromStream.join("\n")) throw new Error(`${file}: indexed and streamed readings differ`);
for (const l of fromIndex) console.log(l);
const s = indexed.statistics;
console.log(`statistics messages ${s.messageCount} schemas ${s.schemaCount} channels ${s.channelCount} chunks ${s.chunkCount} ` +
            `chunk_indexes ${indexed.chunkIndexes.length} compression ${[...new Set(indexed.chunkIndexes.map((c) => c.compression))].join(",")}`);
