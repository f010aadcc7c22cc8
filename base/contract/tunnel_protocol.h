// The adb tunnel's wire protocol: what hitl (the host side, engine/net/adb_tunnel.h) and
// hitl-adb-relay (the board side) agree on. Portable C++17, standard library only: the relay is
// built for the board from this folder alone. docs/adb.md describes it byte by byte.
//
// `adb forward` carries TCP only. The host frames each UDP datagram onto one TCP stream, tagged
// with its logical channel; the relay turns it back into a datagram to the board's port for that
// channel and sends the board's replies back the same way.
//
//   stream  = hello, then frames, in each direction
//   hello   = magic "hitl-adb" (8 bytes) | version (u16) | max_datagram_bytes (u16)     12 bytes
//   frame   = payload_length (u16) | channel (u8) | payload (payload_length bytes)      3 + n bytes
//   integers are big-endian; payload_length <= kMaxDatagram_bytes; channel one of Channel.
#pragma once

#include <cstddef>
#include <cstdint>

#include "base/contract/board_ports.h"

namespace hitl::adb {

/// Bumped whenever the stream's format changes; both ends must speak the same one.
inline constexpr uint16_t kProtocolVersion = 1;
/// The first bytes of every hello: a stream that starts otherwise is not a hitl tunnel.
inline constexpr char kHelloMagic[8] = {'h', 'i', 't', 'l', '-', 'a', 'd', 'b'};
inline constexpr std::size_t kHelloSize_bytes = 12;  ///< 8 magic + 2 version + 2 max datagram
inline constexpr std::size_t kFrameHeaderSize_bytes = 3;  ///< 2 length + 1 channel
/// The largest datagram either end carries; larger ones are dropped and counted. MAVLink over UDP
/// stays under one Ethernet MTU (1472 bytes); this leaves room for batched frames.
inline constexpr std::size_t kMaxDatagram_bytes = 8192;

/// The relay's TCP port on the board (`adb forward tcp:LOCAL tcp:14590`).
inline constexpr uint16_t kRelayTcpPort = kAdbRelayTcpPort;
/// Where a relay pushed by hitl lives on the board when the board package is not installed.
inline constexpr const char* kPushedRelayPath = "/tmp/hitl-adb-relay";
/// Where a relay started with --daemon (as hitl starts it) logs, unless told otherwise.
inline constexpr const char* kRelayDaemonLogPath = "/tmp/hitl-adb-relay.log";
/// The relay's program name (the board package installs it as /usr/bin/hitl-adb-relay).
inline constexpr const char* kRelayProgram = "hitl-adb-relay";

/// The logical ports carried by one stream.
enum class Channel : uint8_t {
  Control = 0,  ///< the tunnel's own messages (ControlType), never forwarded
  Hil = 1,      ///< the board's primary MAVLink instance: HIL_SENSOR / HIL_GPS in, HIL_ACTUATOR_CONTROLS out
  Vio = 2,      ///< voxl-hitl-vio-server: ODOMETRY in
  Gcs = 3,      ///< the board's tertiary (GCS forwarding) MAVLink instance: commands, params, shell
};
inline constexpr std::size_t kChannelCount = 4;
/// The channels that carry datagrams, in order.
inline constexpr Channel kDataChannels[] = {Channel::Hil, Channel::Vio, Channel::Gcs};

inline constexpr bool is_known_channel(uint8_t value) { return value < kChannelCount; }
inline constexpr std::size_t index_of(Channel c) { return static_cast<std::size_t>(c); }
inline constexpr const char* to_string(Channel c) {
  switch (c) {
    case Channel::Control: return "control";
    case Channel::Hil: return "HIL";
    case Channel::Vio: return "VIO";
    case Channel::Gcs: return "GCS";
  }
  return "?";
}

/// The relay's own source ports toward the board's ports (kBoardHilPort, kBoardVioPort,
/// kBoardGcsPort). A PX4 MAVLink instance keeps the first sender it heard until it restarts, so the
/// relay always sends from the same ports, the ones the simulator and direct commands use on the
/// host; a restarted relay is answered again at once.
inline constexpr uint16_t kRelayHilSourcePort = kSimLocalPort;
inline constexpr uint16_t kRelayGcsSourcePort = kDirectLocalPort;

/// Control channel messages: type (u8) | value (u64), 9 bytes.
enum class ControlType : uint8_t {
  Ping = 1,  ///< host -> relay, value: the host's clock; the relay answers at once
  Pong = 2,  ///< relay -> host, value: the ping's value, echoed
};
inline constexpr std::size_t kControlSize_bytes = 9;

}  // namespace hitl::adb
