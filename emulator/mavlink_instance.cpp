#include "emulator/mavlink_instance.h"

namespace hitl::target {

Expected<std::unique_ptr<MavlinkInstance>> MavlinkInstance::open(const std::string& name, const std::string& bind_address,
                                                                 uint16_t port, const mavlink::MessageSet& messages,
                                                                 uint8_t sysid, uint8_t compid) {
  net::UdpEndpoint::Config c;
  c.name = name;
  c.bind_address = bind_address;
  c.bind_port = port;
  c.policy = net::PartnerPolicy::FirstSender;
  auto ep = net::UdpEndpoint::open(c);
  if (!ep) return ep.error();
  return std::unique_ptr<MavlinkInstance>(new MavlinkInstance(name, std::move(ep.value()), messages, sysid, compid));
}

MavlinkInstance::MavlinkInstance(std::string name, net::UdpEndpoint endpoint, const mavlink::MessageSet& messages,
                                 uint8_t sysid, uint8_t compid)
    : name_(std::move(name)), endpoint_(std::move(endpoint)), parser_(messages), encoder_(sysid, compid) {}

void MavlinkInstance::poll(const FrameHandler& on_frame) {
  while (auto d = endpoint_.receive()) {
    if (endpoint_.partner() && d->from != *endpoint_.partner()) ++stats_.ignored_not_partner;
    parser_.parse_datagram(d->bytes, [&](const mavlink::Frame& f) {
      ++stats_.frames_in;
      on_frame(f, *this);
    });
  }
}

void MavlinkInstance::send_bytes(std::span<const uint8_t> bytes) {
  if (!endpoint_.partner()) {
    ++stats_.not_sent_no_partner;
    return;
  }
  if (endpoint_.send(bytes)) ++stats_.frames_out;
}

void MavlinkInstance::set_interval_us(uint32_t msgid, int64_t interval_us) {
  if (interval_us <= 0) {
    streams_.erase(msgid);
    return;
  }
  streams_[msgid] = Stream{interval_us, 0};
}

std::optional<int64_t> MavlinkInstance::interval_us(uint32_t msgid) const {
  auto it = streams_.find(msgid);
  if (it == streams_.end()) return std::nullopt;
  return it->second.interval_us;
}

void MavlinkInstance::restart_streams() {
  for (auto& [id, s] : streams_) s.next_us = 0;
}

std::vector<uint32_t> MavlinkInstance::due_streams(int64_t now_us) {
  std::vector<uint32_t> due;
  for (auto& [id, s] : streams_) {
    if (now_us < s.next_us) continue;
    due.push_back(id);
    s.next_us = (s.next_us == 0 || now_us - s.next_us > s.interval_us) ? now_us + s.interval_us : s.next_us + s.interval_us;
  }
  return due;
}

}  // namespace hitl::target
