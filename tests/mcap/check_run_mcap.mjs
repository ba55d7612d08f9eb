// Checks a run's run.mcap with MCAP's own TypeScript reader (@mcap/core) and Foxglove's OMG IDL
// deserialiser (@foxglove/omgidl-serialization with @foxglove/omgidl-parser), as Foxglove reads
// it, against the run's summary.json and trace.csv:
//   - the stream reader reads every record with every CRC checked; the indexed reader reads the
//     summary, the chunk indexes and every message;
//   - every channel's message count equals the statistics' and what the fleet published: one
//     PlantTick per tick, one AgentReply per agent per tick, one GroupStatus per group per tick,
//     one CentralCommand per tick;
//   - every PlantTick decoded here equals the trace.csv row of its tick.
// Usage: node check_run_mcap.mjs RUN_DIR        Exit 0 when every check passes.
import fs from "node:fs";
import { McapIndexedReader, McapStreamReader } from "@mcap/core";
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
const stream = new McapStreamReader({ validateCrcs: true });
stream.append(bytes);
const kinds = {};
for (let r; (r = stream.nextRecord()); ) kinds[r.type] = (kinds[r.type] ?? 0) + 1;
check("stream reader reads every record to the footer", stream.done(), JSON.stringify(kinds));

// 2. The indexed reader and Foxglove's deserialiser.
const readable = {
  size: async () => BigInt(bytes.length),
  read: async (offset, size) => bytes.subarray(Number(offset), Number(offset + size)),
};
const reader = await McapIndexedReader.Initialize({ readable });
const decoders = new Map();
for (const [id, s] of reader.schemasById) {
  check(`schema ${s.name} is omgidl`, s.encoding === "omgidl");
  decoders.set(id, new MessageReader(s.name, parseIDL(new TextDecoder().decode(s.data))));
}
const byTopic = {};
for (const ch of reader.channelsById.values()) byTopic[ch.topic] = [];
for await (const m of reader.readMessages()) {
  const ch = reader.channelsById.get(m.channelId);
  byTopic[ch.topic].push(decoders.get(ch.schemaId).readMessage(m.data));
}
const stats = reader.statistics;
console.log(
  `run.mcap: ${bytes.length} bytes, ${reader.channelsById.size} channels, ${stats.messageCount} messages, ` +
    `${reader.chunkIndexes.length} chunks`,
);
for (const ch of reader.channelsById.values()) {
  const n = byTopic[ch.topic].length;
  console.log(`  ${ch.topic.padEnd(20)} ${String(n).padStart(8)}  ${reader.schemasById.get(ch.schemaId).name}`);
  check(`${ch.topic}: statistics count`, Number(stats.channelMessageCounts.get(ch.id)) === n);
}

// 3. Counts against what the fleet published.
const ticks = byTopic["maptr/tick"] ?? [];
const tickSet = new Set(ticks.map((t) => Number(t.tick)));
check("one PlantTick per tick", tickSet.size === ticks.length && ticks.length === summary.ticks + 1,
      `${ticks.length} PlantTicks, ${tickSet.size} distinct, summary ticks ${summary.ticks}`);
function perTick(topic, per, key) {
  const msgs = byTopic[topic] ?? [];
  const seen = new Map();
  for (const m of msgs) {
    const k = `${Number(m.tick)}/${key(m)}`;
    seen.set(k, (seen.get(k) ?? 0) + 1);
  }
  const dup = [...seen.values()].filter((v) => v > 1).length;
  const answered = new Set(msgs.map((m) => Number(m.tick)));
  const ok = dup === 0 && msgs.length === answered.size * per && [...answered].every((k) => tickSet.has(k));
  check(`${topic}: ${per} per tick answered`, ok, `${msgs.length} messages over ${answered.size} ticks`);
  return answered.size;
}
const n = countAgents(summary);
const answeredByAgents = perTick("maptr/agent_reply", n, (m) => `${m.side}/${m.index}`);
perTick("maptr/group", 2, (m) => m.side);
perTick("maptr/central", 1, () => 0);
check("agents answer every tick but the last", answeredByAgents === ticks.length - 1,
      `${answeredByAgents} of ${ticks.length}`);

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
