#pragma once
// What the fleet makes of one recorded sample, judged from its writer and its bytes alone: the
// recorder marks each sample of run.mcap with it, so that a replay republishes only what the
// fleet could have taken. The rules are the fleet's own, in the order its readers apply them
// (docs/ARCHITECTURE.md, "Bad input"): a sample must decode as its type (else undecodable),
// come from the process that publishes its topic (comm::published_topics), identified by its
// writer's GUID prefix or certificate (else forged), hold the type's rule (idl/rules.hpp; else
// malformed), and state its sender: an agent's reply must name that agent, a group's status
// that group's side, a NodeReady its own process (else forged). The takers' further judgements of timing
// (a late answer, a second answer to one tick, a stale membership event) and the plant's
// voltage bound are not made here: such samples are recorded as taken. No DDS, no file.
#include <cstdint>
#include <string>

namespace maptr::recorder {

/// Why the fleet drops a sample; kTaken when it does not.
enum class Verdict : uint8_t { kTaken, kForged, kUndecodable, kMalformed };

/// "taken", "forged", "undecodable", "malformed".
const char* verdict_name(Verdict v);

/// The verdict on `bytes` (a sample as sent) on fleet topic `topic`, written by process
/// `writer` ("" for a writer of no process of the fleet), in a fleet of `agents` agents.
/// A topic the fleet does not have is forged.
Verdict judge_sample(const std::string& topic, const std::string& bytes, const std::string& writer,
                     int agents);

}  // namespace maptr::recorder
