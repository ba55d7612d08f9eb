#pragma once
// A reader's listener that takes every sample and keeps none: for a reader whose only purpose is
// that its writers reach this participant before the lock-step starts (topic::kHello, the ports).
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

namespace maptr::comm {

template <class T>
class Discard : public eprosima::fastdds::dds::DataReaderListener {
 public:
  void on_data_available(eprosima::fastdds::dds::DataReader* r) override {
    T sample;
    eprosima::fastdds::dds::SampleInfo info;
    while (r->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
    }
  }
};

}  // namespace maptr::comm
