#pragma once
// The tick filter: a Fast DDS content filter (IContentFilterFactory) that lets an agent take
// only the ticks comm::tick_wakes_agent says it needs. Registered on the plant's participant,
// whose tick writer then evaluates it for each agent's reader before sending (writer-side
// filtering: an idle agent is not woken at all for the nine ticks in ten it does not answer),
// and on each agent's participant, whose reader evaluates it for samples the writer did not
// filter. A tick that does not decode is delivered: the follower's checks then reject it.
#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/topic/ContentFilteredTopic.hpp>
#include <fastdds/dds/topic/Topic.hpp>

namespace maptr::comm {

/// The filter class name both sides register.
inline constexpr const char* kTickFilterClass = "MAPTR_TICK_WAKE";

/// Registers the tick filter's factory on participant `dp` (once; later calls do nothing).
void register_tick_filter(eprosima::fastdds::dds::DomainParticipant* dp);

/// The filtered view of tick topic `tick` for agent `index` of `side` (registers the filter).
eprosima::fastdds::dds::ContentFilteredTopic* agent_tick_topic(eprosima::fastdds::dds::DomainParticipant* dp,
                                                               eprosima::fastdds::dds::Topic* tick, int side,
                                                               int index);

/// Writer-side filters the plant's tick writer keeps: one per agent's reader, with room to spare
/// for restarted agents whose old reader is not yet unmatched.
inline int tick_filter_capacity(int agents) { return 2 * agents + 16; }

}  // namespace maptr::comm
