// LD_PRELOAD library for tools/secure_race.sh: wraps Fast DDS 2.9.1's
// SecurityManager::match_builtin_endpoints, which fills one member of the participant's
// SecurityManager (temp_stateless_reader_proxy_data_) without a lock, and counts the calls
// that run while another call on the same SecurityManager is still inside (each one may
// overwrite the other's proxy data: the race behind the discovery abort
// `StatelessWriter::matched_reader_add: data.guid() != c_Guid_Unknown`).
//
// Environment: MATCH_SHIM_SERIALISE=1 takes a lock around each call (the upstream fix's
// effect); MATCH_SHIM_PAUSE_US=N sleeps N µs inside each call (widens the window, as load
// does). At exit it prints one line on stderr (the process's log in a fleet):
//   match_shim: pid P calls C overlapping O serialised 0|1
#include <dlfcn.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <thread>

namespace eprosima::fastrtps::rtps {
class ParticipantProxyData;
namespace security {
class SecurityManager {
 public:
  bool match_builtin_endpoints(const ParticipantProxyData& remote);
};
}  // namespace security
}  // namespace eprosima::fastrtps::rtps

namespace {
using Sm = eprosima::fastrtps::rtps::security::SecurityManager;
using Ppd = eprosima::fastrtps::rtps::ParticipantProxyData;
// The member function's ABI: `this` as the first argument.
using Original = bool (*)(Sm*, const Ppd&);

constexpr const char* kSymbol =
    "_ZN8eprosima8fastrtps4rtps8security15SecurityManager23match_builtin_endpointsERKNS1_20ParticipantProxyDataE";

struct State {
  Original original = nullptr;
  bool serialise = false;
  long pause_us = 0;
  std::mutex lock;
  std::atomic<Sm*> inside{nullptr};  // the SecurityManager a call is inside, or null
  std::atomic<int> depth{0};
  std::atomic<long> calls{0};
  std::atomic<long> overlapping{0};

  State() {
    original = reinterpret_cast<Original>(dlsym(RTLD_NEXT, kSymbol));
    const char* s = std::getenv("MATCH_SHIM_SERIALISE");
    serialise = s && s[0] == '1';
    if (const char* p = std::getenv("MATCH_SHIM_PAUSE_US")) pause_us = std::strtol(p, nullptr, 10);
  }
  ~State() {
    if (calls.load() > 0)
      std::fprintf(stderr, "match_shim: pid %d calls %ld overlapping %ld serialised %d\n", getpid(), calls.load(),
                   overlapping.load(), serialise ? 1 : 0);
  }
};

State& state() {
  static State s;
  return s;
}

bool call(State& s, Sm* self, const Ppd& remote) {
  ++s.calls;
  // A fleet process has one participant, hence one SecurityManager: a second call while one is
  // inside is an overlap on the same member.
  if (s.depth.fetch_add(1) > 0 && s.inside.load() == self) ++s.overlapping;
  s.inside = self;
  if (s.pause_us > 0) std::this_thread::sleep_for(std::chrono::microseconds(s.pause_us));
  const bool r = s.original(self, remote);
  s.depth.fetch_sub(1);
  return r;
}
}  // namespace

bool Sm::match_builtin_endpoints(const Ppd& remote) {
  State& s = state();
  if (!s.original) std::abort();  // not Fast DDS 2.9's library: nothing to wrap
  if (!s.serialise) return call(s, this, remote);
  std::lock_guard<std::mutex> g(s.lock);
  return call(s, this, remote);
}
