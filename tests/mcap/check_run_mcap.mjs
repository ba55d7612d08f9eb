// Checks a run's run.mcap with MCAP's own TypeScript reader (@mcap/core, with the zstd and lz4
// decompressors of @mcap/support, as Foxglove loads them) and Foxglove's OMG IDL
// deserialiser (@foxglove/omgidl-serialization with @foxglove/omgidl-parser), as Foxglove reads
// it, against the run's summary.json and trace.csv:
//   - the stream reader reads every record with every CRC checked; the indexed reader reads the
//     summary, the chunk indexes and every message; every chunk is compressed as the run's
//     scenario.yaml says (record_compression);
//   - every channel names its writer (GUID prefix and process) and its message count equals the
//     statistics'; the samples the fleet took (verdict "taken") hold what the fleet published:
//     one PlantTick per tick (and a copy per repair), every answer the lock-step needs, one
//     GroupStatus per group per tick, one CentralCommand per tick;
//   - every PlantTick decoded here equals the trace.csv row of its tick.
// Usage: node check_run_mcap.mjs RUN_DIR        Exit 0 when every check passes.
import fs from "node:fs";
import { McapIndexedReader, McapStreamReader } from "@mcap/core";
import { loadDecompressHandlers } from "@mcap/support";
import { parseIDL } from "@foxglove/omgidl-parser";
import { MessageReader } from "@foxglove/omgidl-serialization";

const run = process.argv[2];
if (!run) {
  console.error("usage: node check_run_mcap.mjs RUN_DIR");
  process.exit(2);
}
let passed = 0;
let failed = 0;
function check(name, ok, detail = "") {
  if (ok) passed++;
  else failed++;
  console.log(`${ok ? "ok  " : "FAIL"} ${name}${detail ? ": " + detail : ""}`);
}

const bytes = fs.readFileSync(`${run}/run.mcap`);
const summary = JSON.parse(fs.readFileSync(`${run}/summary.json`, "utf8"));

// Agents alive at the end (a fault-free run: the fleet size).
function countAgents(s) {
  const live = s.plant?.live_agents ?? {};
  return (live.L ?? 0) + (live.R ?? 0);
}

// 1. The stream reader, every CRC checked.
const decompressHandlers = await loadDecompressHandlers();
const stream = new McapStreamReader({ validateCrcs: true, decompressHandlers });
stream.append(bytes);
const kinds = {};
for (let r; (r = stream.nextRecord()); ) kinds[r.type] = (kinds[r.type] ?? 0) + 1;
check("stream reader reads every record to the footer", stream.done(), JSON.stringify(kinds));

// 2. The indexed reader and Foxglove's deserialiser.
const readable = {
  size: async () => BigInt(bytes.length),
  read: async (offset, size) => bytes.subarray(Number(offset), Number(offset + size)),
};
const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers });
const wanted = (fs.readFileSync(`${run}/scenario.yaml`, "utf8").match(/^record_compression:\s*(\w+)/m) ?? [])[1] ?? "zstd";
const compressions = new Set(reader.chunkIndexes.map((c) => c.compression));
check(
  `every chunk compressed as record_compression says (${wanted})`,
  reader.chunkIndexes.length > 0 && compressions.size === 1 && compressions.has(wanted === "none" ? "" : wanted),
  [...compressions].join(","),
);
const decoders = new Map();
for (const [id, s] of reader.schemasById) {
  check(`schema ${s.name} is omgidl`, s.encoding === "omgidl");
  decoders.set(id, new MessageReader(s.name, parseIDL(new TextDecoder().decode(s.data))));
}
// One channel per topic and writer; its metadata names the writer's GUID prefix, its process and
// the fleet's verdict on its samples ("taken" on a run nobody attacked).
const byTopic = {};
const perChannel = new Map();
for (const ch of reader.channelsById.values()) {
  byTopic[ch.topic] = [];
  perChannel.set(ch.id, 0);
  check(`${ch.topic} channel ${ch.id} names its writer`,
        /^[0-9a-f]{24}$/.test(ch.metadata.get("writer") ?? "") && (ch.metadata.get("process") ?? "") !== "",
        JSON.stringify([...ch.metadata]));
}
for await (const m of reader.readMessages()) {
  const ch = reader.channelsById.get(m.channelId);
  perChannel.set(ch.id, perChannel.get(ch.id) + 1);
  if (ch.metadata.get("verdict") === "taken") byTopic[ch.topic].push(decoders.get(ch.schemaId).readMessage(m.data));
}
const stats = reader.statistics;
console.log(
  `run.mcap: ${bytes.length} bytes, ${reader.channelsById.size} channels, ${stats.messageCount} messages, ` +
    `${reader.chunkIndexes.length} chunks (${[...compressions].join(",") || "uncompressed"})`,
);
for (const topic of Object.keys(byTopic).sort())
  console.log(`  ${topic.padEnd(20)} ${String(byTopic[topic].length).padStart(8)} taken`);
for (const ch of reader.channelsById.values())
  check(`${ch.topic} channel ${ch.id}: statistics count`,
        Number(stats.channelMessageCounts.get(ch.id)) === perChannel.get(ch.id));

// 3. Counts against what the fleet published: one PlantTick per tick, and a copy for every
// tick the plant sent again (plant.tick_repairs); every answer the lock-step needs (an agent
// answers every tick it is assigned in, every 10th while idle in a slot of its own, and its
// first; groups and central every tick). A repeated tick is answered again: copies are allowed.
const ticks = byTopic["maptr/tick"] ?? [];
const tickSet = new Set(ticks.map((t) => Number(t.tick)));
const repairs = Number(summary.plant?.tick_repairs ?? 0);
check("one PlantTick per tick, a copy per repair",
      tickSet.size === summary.ticks + 1 && ticks.length === summary.ticks + 1 + repairs,
      `${ticks.length} PlantTicks, ${tickSet.size} distinct, summary ticks ${summary.ticks}, repairs ${repairs}`);
const sent = new Map(ticks.map((t) => [Number(t.tick), t]));
function answers(topic, key) {
  return new Set((byTopic[topic] ?? []).map((m) => `${Number(m.tick)}/${key(m)}`));
}
const n = countAgents(summary);
const perSide = n / 2;
const replies = answers("maptr/agent_reply", (m) => `${m.side}/${m.index}`);
let missing = 0;
for (let k = 0; k < summary.ticks; ++k)
  for (let side = 0; side < 2; ++side)
    for (let j = 0; j < perSide; ++j) {
      const active = sent.get(k).sides[side].active[j] !== 0;
      const due = (k + side * perSide + j) % 10 === 0;
      if ((k === 0 || active || due) && !replies.has(`${k}/${side}/${j}`)) ++missing;
    }
check("maptr/agent_reply: every needed answer", missing === 0, `${replies.size} distinct answers, ${missing} missing`);
const statuses = answers("maptr/group", (m) => m.side);
check("maptr/group: 2 per tick answered", statuses.size === 2 * summary.ticks, `${statuses.size} distinct`);
const commands = answers("maptr/central", () => 0);
check("maptr/central: 1 per tick answered", commands.size === summary.ticks, `${commands.size} distinct`);

// 4. PlantTick against trace.csv.
const lines = fs.readFileSync(`${run}/trace.csv`, "utf8").trim().split("\n");
const head = lines[0].split(",");
const col = (name) => head.indexOf(name);
const tickOf = new Map(ticks.map((t) => [Number(t.tick), t]));
const fields = [
  ["t_s", (t) => t.t], ["x_m", (t) => t.x], ["y_m", (t) => t.y], ["theta_rad", (t) => t.theta],
  ["v_x_mps", (t) => t.v_x], ["w_radps", (t) => t.w], ["energy_J", (t) => t.energy_J],
  ["distance_m", (t) => t.distance_m],
  ["phidot_L_radps", (t) => t.sides[0].phidot], ["phidot_R_radps", (t) => t.sides[1].phidot],
  ["battery_V_L", (t) => t.sides[0].battery_V], ["battery_V_R", (t) => t.sides[1].battery_V],
  ["discharge_L_mAh", (t) => t.sides[0].discharge_mAh], ["discharge_R_mAh", (t) => t.sides[1].discharge_mAh],
  ["ref_L_radps", (t) => t.sides[0].phidot_ref], ["ref_R_radps", (t) => t.sides[1].phidot_ref],
  ["n_active_L", (t) => t.sides[0].n_active], ["n_active_R", (t) => t.sides[1].n_active],
];
let compared = 0;
const mismatches = [];
for (const line of lines.slice(1)) {
  const v = line.split(",");
  const t = tickOf.get(Number(v[col("tick")]));
  if (!t) {
    mismatches.push(`no PlantTick for trace tick ${v[col("tick")]}`);
    continue;
  }
  for (const [name, get] of fields) {
    // PlantTick 0 goes out before central's first command: no reference is in force yet; its
    // trace row shows the reference then applied over [t_0, t_1].
    if (Number(t.tick) === 0 && name.startsWith("ref_")) continue;
    const a = Number(v[col(name)]);
    const b = Number(get(t));
    // trace.csv prints 9 significant digits (t_s: 6 decimals).
    if (Math.abs(a - b) > 1e-8 * Math.abs(b) + 1e-6) mismatches.push(`tick ${t.tick} ${name}: trace ${a}, PlantTick ${b}`);
  }
  compared++;
}
check(`every trace.csv row equals its decoded PlantTick (${compared} rows, ${fields.length} fields)`,
      mismatches.length === 0 && compared === lines.length - 1, `${mismatches.length} differences: ` + mismatches.slice(0, 5).join("; "));
const mid = tickOf.get(Math.floor(ticks.length / 2));
if (mid) console.log(`PlantTick ${mid.tick}: t=${mid.t} v_x=${mid.v_x} energy_J=${mid.energy_J} ` +
                     `battery_V L=${mid.sides[0].battery_V} active L=${mid.sides[0].n_active} R=${mid.sides[1].n_active}`);

console.log(`${passed} passed, ${failed} failed`);
process.exit(failed === 0 ? 0 : 1);
