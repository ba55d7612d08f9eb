#pragma once
// The fleet's recorder: a read-only DDS participant whose readers take every sample on the
// fleet's topics as raw CDR (comm/dds/raw_type.hpp) and a thread that writes them to run.mcap
// (records/mcap.hpp), each with its log time (wall clock when taken, ns since the Unix epoch)
// and its publish time (the writer's source timestamp). The readers keep a history deeper than
// one tick's burst of replies and hand samples over at once, so the recorder neither slows the
// fleet's reliable writers nor loses samples; the file is written off the DDS threads, by a
// thread that takes the queued samples in batches (every 50 ms or 512 samples). Each sample
// goes to the channel of its topic, its writer and the fleet's verdict on it
// (recorder/sample_verdict.hpp): the channel's metadata names the writer's GUID prefix
// (kWriterKey), its process (kProcessKey, "" for none of the fleet's) and the verdict
// (kVerdictKey: "taken", or why the fleet drops such a sample).
#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "comm/dds/dds.hpp"
#include "comm/dds/raw_type.hpp"
#include "recorder/sample_verdict.hpp"
#include "records/mcap.hpp"

namespace maptr::recorder {

/// What a recording holds: every topic, the plant's (ticks, fault gates) with the fleet's
/// events (membership, control, ready), or nothing.
enum class Scope { kAll, kPlant, kNone };

/// "all" | "plant" | "none" (the scenario's `record` field); throws std::invalid_argument.
Scope parse_scope(const std::string& text);

/// The topics a recording of `scope` holds.
std::vector<comm::FleetTopic> recorded_topics(Scope scope);

/// Samples each of a fleet of `agents` agents' writers may send before the recorder takes
/// them: the history depth of its readers.
int32_t recorder_depth(int agents);

/// Keys of a run.mcap channel's metadata: its writer's GUID prefix (24 hexadecimal digits), the
/// process of the fleet that writer belongs to ("" for none) and the verdict on its samples.
inline constexpr const char* kWriterKey = "writer";
inline constexpr const char* kProcessKey = "process";
inline constexpr const char* kVerdictKey = "verdict";

/// Makes the recorders this process creates from now on blind to the answer writer of agent
/// `name`'s first start ("" for none): they neither record nor count it, as if discovery had
/// failed on the recorder's side only. A seam for the tests' hooked launcher (tests/hooks); the
/// product sets none.
void hide_first_answer_writer_of(const std::string& name);

class Recorder {
 public:
  /// Joins the domain of `o` (a participant of its own) and opens `path`. Throws
  /// records::RecordError when the file cannot be written, std::runtime_error on DDS errors.
  /// `compression`: run.mcap's chunk compression as MCAP names it ("", "zstd" or "lz4").
  Recorder(const comm::DdsOptions& o, const std::string& path, Scope scope, int agents,
           const std::string& compression = "zstd");
  ~Recorder();
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  /// Waits until each topic in `writers` has matched at least that many writers; false at the
  /// deadline (the topics that lack writers are then in missing()).
  bool wait_matched(const std::map<std::string, int>& writers,
                    std::chrono::steady_clock::time_point deadline);
  std::string missing() const { return missing_; }
  /// The writers of `topic` the recorder has matched (their GUIDs, comm/dds/fleet_guid.hpp).
  std::vector<eprosima::fastrtps::rtps::InstanceHandle_t> matched_writers(const std::string& topic) const;
  /// Leaves the domain, writes what is left and closes the file (once).
  void stop();
  /// Messages recorded per topic so far.
  std::map<std::string, uint64_t> counts() const;
  /// Messages written so far that the fleet drops, by verdict ("forged", "undecodable",
  /// "malformed"; kinds without any left out).
  std::map<std::string, uint64_t> rejected() const;

 private:
  /// One sample taken from DDS, waiting for the file.
  struct Pending {
    uint16_t topic;  ///< index in topics_
    eprosima::fastrtps::rtps::InstanceHandle_t writer;
    uint64_t log_ns, publish_ns;
    std::string bytes;
  };
  /// A channel of the file: a topic, a writer and the verdict on its samples.
  struct ChannelKey {
    uint16_t topic;
    eprosima::fastrtps::rtps::InstanceHandle_t writer;
    Verdict verdict;
    bool operator<(const ChannelKey& o) const {
      if (topic != o.topic) return topic < o.topic;
      if (writer != o.writer) return writer < o.writer;
      return verdict < o.verdict;
    }
  };
  class Tap;
  void push(uint16_t topic, const eprosima::fastrtps::rtps::InstanceHandle_t& writer,
            const eprosima::fastrtps::rtps::Time_t& source, std::string&& bytes);
  /// On the file thread: the channel of `p`, added to the file at its first sample.
  uint16_t channel_of(const Pending& p);
  /// On a receive thread, before it takes: naps when a sample woke it from a wait.
  void nap_if_woken();
  /// On a receive thread, after it took.
  void taken();
  void write_loop();

  std::vector<comm::FleetTopic> topics_;
  uint32_t fleet_id_;
  int agents_;
  std::vector<uint16_t> schema_;  ///< per topic
  // The file thread's own:
  std::map<eprosima::fastrtps::rtps::InstanceHandle_t, std::string> writers_;  ///< writer -> process
  std::map<ChannelKey, uint16_t> channels_;
  std::vector<uint32_t> sequence_;  ///< per channel
  std::array<std::atomic<uint64_t>, 4> verdicts_{};
  std::unique_ptr<records::mcap::Writer> file_;
  std::vector<std::unique_ptr<Tap>> taps_;
  std::unique_ptr<comm::Participant> participant_;
  mutable std::mutex m_;
  std::condition_variable cv_;
  std::deque<Pending> queue_;
  std::vector<uint64_t> counts_;
  bool stopping_ = false;
  std::thread writer_;
  std::string missing_;
  std::atomic<int64_t> last_take_ns_{0};  ///< steady clock, when a receive thread last took
};

}  // namespace maptr::recorder
