#include "engine/hil/stack_peer.h"

#include <cctype>

namespace hitl::hil {
namespace {

bool all_digits(std::string_view text) {
  if (text.empty()) return false;
  for (const char c : text)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

}  // namespace

Expected<net::LinkSpec> parse_px4_sitl(std::string_view text, const std::string& target_ip) {
  std::string spelled(text);
  // The spellings before the link grammar: tcp:PORT (hitl listens) and udp:PORT (PX4 at -i).
  if (spelled.rfind("tcp:", 0) == 0 && all_digits(text.substr(4))) spelled = "tcpin:" + spelled.substr(4);
  else if (spelled.rfind("udp:", 0) == 0 && all_digits(text.substr(4)))
    spelled = "udp:" + (target_ip.find(':') != std::string::npos ? "[" + target_ip + "]" : target_ip) + ":" + spelled.substr(4);
  auto spec = net::parse_link_spec(spelled);
  if (!spec) {
    Error e = spec.error();
    if (spelled != text) e = e.prefixed("'" + std::string(text) + "' as ");
    return e;
  }
  spec->text = std::string(text);
  const std::string what = "'" + spec->text + "'";
  if (spec->kind == net::LinkSpec::Kind::Tcp)
    return Error::input(what + ": PX4 SITL connects to the simulator, never the other way: tcpin:PORT (hitl listens, "
                               "default tcpin:4560)");
  if (spec->kind == net::LinkSpec::Kind::UdpIn)
    return Error::input(what + ": PX4 SITL's UDP simulator link waits for the simulator to send first: udp:HOST:PORT "
                               "(PX4's port, e.g. udp:127.0.0.1:14560)");
  return spec;
}

Expected<StackPeer> StackPeer::decide(const SessionConfig& config, const std::optional<px4::Px4Instance>& owned) {
  net::LinkSettings settings;
  settings.bind_address = config.bind_address;
  if (owned) {
    net::LinkSpec sim;  // PX4 connects to 127.0.0.1 (PX4_SIM_HOSTNAME unset), so hitl listens there only
    sim.kind = net::LinkSpec::Kind::TcpIn;
    sim.host = "127.0.0.1";
    sim.port = owned->simulator_tcp_port();
    sim.text = sim.to_string();
    settings.bind_address = "127.0.0.1";
    settings.name = "PX4's simulator port (instance " + std::to_string(owned->index) + ")";
    settings.max_clients = 1;
    StackPeer peer(Flavour::Px4Owned, true, std::move(sim), std::move(settings));
    peer.instance_ = owned;
    peer.telemetry_settings_.name = "PX4's GCS MAVLink port (instance " + std::to_string(owned->index) + ")";
    peer.telemetry_settings_.host_what = "PX4's GCS port";
    peer.telemetry_settings_.bind_address = "127.0.0.1";
    peer.telemetry_settings_.hear_peer_only = true;  // PX4 answers from its GCS port
    return peer;
  }
  if (!config.px4_sitl) {
    net::LinkSpec board;
    board.kind = net::LinkSpec::Kind::Udp;
    board.host = config.target_ip;
    board.port = config.hil_port;
    board.text = board.to_string();
    settings.name = "HIL link (--local-port)";
    settings.host_what = "-i (the board's address)";
    settings.local_port = config.local_port;
    settings.hear_peer_only = true;  // PX4 answers from its own port; anything else is not our board
    return StackPeer(Flavour::Board, config.lockstep, std::move(board), std::move(settings));
  }
  const net::LinkSpec& sitl = *config.px4_sitl;
  if (sitl.kind == net::LinkSpec::Kind::Udp) {
    settings.name = "HIL link (--local-port)";
    settings.host_what = "--px4-sitl";
    settings.local_port = config.local_port;
    settings.hear_peer_only = true;
  } else if (sitl.kind == net::LinkSpec::Kind::TcpIn) {
    settings.name = "--px4-sitl";
    settings.max_clients = 1;  // PX4 connects once and never reconnects
  } else {
    return Error::input("--px4-sitl '" + sitl.text + "': PX4 SITL's simulator link is tcpin:[HOST:]PORT or udp:HOST:PORT");
  }
  return StackPeer(Flavour::Px4Sitl, true, sitl, std::move(settings));
}

std::optional<net::LinkSpec> StackPeer::telemetry_link() const {
  if (flavour_ != Flavour::Px4Owned || !instance_) return std::nullopt;
  net::LinkSpec gcs;
  gcs.kind = net::LinkSpec::Kind::Udp;
  gcs.host = "127.0.0.1";
  gcs.port = instance_->gcs_udp_port();
  gcs.text = gcs.to_string();
  return gcs;
}

std::string StackPeer::start_hint() const {
  if (flavour_ == Flavour::Board) return "start the flight stack now";
  if (flavour_ == Flavour::Px4Owned) return "hitl started it as instance " + std::to_string(instance_ ? instance_->index : 0);
  return "start PX4 now, in its build tree: PX4_SYS_AUTOSTART=10016 PX4_SIM_MODEL=none_iris build/px4_sitl_default/bin/px4 "
         "(docs/sim.md adds the x500 geometry as PX4_PARAM_ variables)";
}

std::string StackPeer::no_answer_cause(const std::string& peer, double warning_s) const {
  if (flavour_ == Flavour::Px4Owned)
    return "no HIL_ACTUATOR_CONTROLS from the PX4 hitl started yet; still sending (its console says why)";
  if (flavour_ == Flavour::Px4Sitl)
    return "no HIL_ACTUATOR_CONTROLS from PX4 SITL yet; still sending. Is PX4 started with a simulator "
           "airframe (e.g. 10016 none_iris)?";
  return "no HIL_ACTUATOR_CONTROLS from " + peer + " within " + std::to_string(static_cast<int>(warning_s)) +
         " s of the first HIL_SENSOR; still sending (with no board by design, as in the spec's Phase 1, nothing more "
         "is wrong). With a board, likely causes: its HIL instance is locked to an earlier session's port (restart "
         "PX4 on the board: voxl-px4-hitl start), HIL is not enabled (SYS_HITL must be 1), or the wrong IP (-i)";
}

std::string StackPeer::lost_text() const {
  if (flavour_ == Flavour::Px4Owned) return "PX4 closed the simulator link; this session ends";
  return std::string(name()) + " disconnected; PX4 never reconnects to a simulator, so this session ends (restart PX4 and "
                               "hitl sim together)";
}

}  // namespace hitl::hil
