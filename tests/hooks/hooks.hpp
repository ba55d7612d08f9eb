#pragma once
// Test hooks: what the tests' hooked binaries (build/hooked-bin) read from their environment.
// Each is installed, before main, into a seam the product offers and leaves empty:
//   MAPTR_TEST_SILENT_ONCE=NAME:PATH   process NAME withholds its NodeReady while the file PATH
//                                      does not exist, and creates it (comm::set_ready_gate)
//   MAPTR_TEST_ABORT_ONCE=NAME:PATH    process NAME aborts (SIGABRT, as a failed assertion in
//                                      Fast DDS does) where it would report ready, once
//   MAPTR_TEST_RECORDER_DEAF_TO=NAME   the launcher's recorder does not see the first start of
//                                      agent NAME's answer writer (recorder::hide_first_answer_writer_of)
//   MAPTR_TEST_PLANT_BLIND_TO=NAME     the plant's discovery does not count the first start of
//                                      agent NAME's answer writer (plant::hide_first_answer_writer_of)
//   MAPTR_TEST_LEVEL2_DELAY_MS=MS      every Level-2 solve of a group takes MS longer, 0..10000
//                                      (group::set_level2_pause)
// The product's binaries (build/bin) read none of them.
namespace maptr::test_hooks {

inline constexpr const char* kSilentOnceEnv = "MAPTR_TEST_SILENT_ONCE";
inline constexpr const char* kAbortOnceEnv = "MAPTR_TEST_ABORT_ONCE";
inline constexpr const char* kRecorderDeafEnv = "MAPTR_TEST_RECORDER_DEAF_TO";
inline constexpr const char* kPlantBlindEnv = "MAPTR_TEST_PLANT_BLIND_TO";
inline constexpr const char* kLevel2DelayEnv = "MAPTR_TEST_LEVEL2_DELAY_MS";
/// The longest Level-2 pause accepted, ms.
inline constexpr long kMaxLevel2DelayMs = 10000;

}  // namespace maptr::test_hooks
