#pragma once
// A thread of the project's own gets a name (/proc/PID/task/TID/comm), so that the benches can
// tell its CPU from the rest of its process's threads (deploy/studies/bench/proc_stats.hpp lists
// the names they read): "level2" for a group's Level-2 solver, "recorder" for run.mcap's writer.
#include <pthread.h>

namespace maptr::comm {

/// The names of the project's own threads (the benches read them back from /proc).
inline constexpr const char* kLevel2Thread = "level2";
inline constexpr const char* kRecorderThread = "recorder";

/// Names the calling thread (at most 15 characters); a name that does not fit is left out.
inline void name_this_thread(const char* name) { pthread_setname_np(pthread_self(), name); }

}  // namespace maptr::comm
