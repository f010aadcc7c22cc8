#include "engine/net/udp_link.h"

namespace hitl::net {

Expected<std::unique_ptr<UdpLink>> UdpLink::open(const Config& config) {
  auto endpoint = UdpEndpoint::open(config.endpoint);
  if (!endpoint) return endpoint.error();
  return std::unique_ptr<UdpLink>(new UdpLink(std::move(endpoint.value()), config));
}

UdpLink::UdpLink(UdpEndpoint endpoint, const Config& config)
    : Link(config.endpoint.name), endpoint_(std::move(endpoint)) {
  if (config.hear_peer_only) only_from_ = config.endpoint.peer;
}

std::size_t UdpLink::read_some(std::size_t max_reads, const ChunkHandler& on_chunk) {
  std::size_t reads = 0;
  for (; reads < max_reads; ++reads) {
    auto d = endpoint_.receive();
    if (!d) break;
    if (only_from_ && d->from != *only_from_) {
      ++stats_.ignored_other_address;
      continue;
    }
    on_chunk(LinkChunk{d->bytes, d->from, /*whole_datagram=*/true});
  }
  sync_stats();
  return reads;
}

Status UdpLink::send(std::span<const uint8_t> bytes) {
  auto st = endpoint_.send(bytes);
  sync_stats();
  return st;
}

void UdpLink::poll_kernel_drops() {
  endpoint_.poll_kernel_drops();
  sync_stats();
}

SendOutcome UdpLink::try_send(std::span<const uint8_t> bytes) {
  SendOutcome out = SendOutcome::Refused;
  if (const auto& to = endpoint_.partner()) out = endpoint_.try_send_to(*to, bytes);
  sync_stats();
  return out;
}

Status UdpLink::flush() {
  if (tx_.empty()) return Ok{};
  auto st = endpoint_.send(tx_);
  tx_.clear();
  sync_stats();
  return st;
}

void UdpLink::sync_stats() {
  const auto& e = endpoint_.stats();
  stats_.datagrams_in = e.datagrams_in;  // every datagram read, ignored ones too, as UdpEndpoint counts
  stats_.datagrams_out = e.datagrams_out;
  stats_.bytes_in = e.bytes_in;
  stats_.bytes_out = e.bytes_out;
  stats_.send_errors = e.send_errors;
  stats_.last_send_errno = e.last_send_errno;
  stats_.kernel_rx_drops = e.kernel_rx_drops;
}

}  // namespace hitl::net
