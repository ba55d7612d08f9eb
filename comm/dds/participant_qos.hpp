#pragma once
// The QoS a Participant is created with, from its DdsOptions: lease, discovery (simple, a
// discovery server's client, or a server), transports (shared memory, UDP on one interface),
// participant id and GUID prefix. Security properties are added by the Participant.
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <string>

#include "comm/dds/dds.hpp"

namespace maptr::comm {

eprosima::fastdds::dds::DomainParticipantQos participant_qos(const std::string& name, const DdsOptions& o);

}  // namespace maptr::comm
