// libFuzzer target for the one link grammar (engine/net/link_spec.h): every --connect, --endpoint,
// --px4-sitl and --gcs value a user types or a config file holds. A value is parsed or refused with words
// that name it; a parsed one spells itself back (to_string) into the same link.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "engine/net/link_spec.h"
#include "tests/fuzz/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(bytes), size);
  // A UDP peer (inspect --connect, sim --gcs): udp:HOST:PORT or HOST:PORT, or refused naming the value.
  auto peer = hitl::net::parse_udp_peer(text, "UDP only");
  if (peer) FUZZ_CHECK(peer->kind == hitl::net::LinkSpec::Kind::Udp && !peer->host.empty() && peer->port != 0);
  else FUZZ_CHECK(peer.error().kind == hitl::ErrorKind::Input && peer.error().message.find(std::string(text)) != std::string::npos);
  auto spec = hitl::net::parse_link_spec(text);
  if (!spec) {
    FUZZ_CHECK(spec.error().kind == hitl::ErrorKind::Input);
    FUZZ_CHECK(spec.error().message.find(std::string(text)) != std::string::npos);
    return 0;
  }
  FUZZ_CHECK(spec->port != 0);
  FUZZ_CHECK(spec->listens() || !spec->host.empty());
  auto again = hitl::net::parse_link_spec(spec->to_string());
  FUZZ_CHECK(again.ok());
  FUZZ_CHECK(again->kind == spec->kind && again->host == spec->host && again->port == spec->port);
  return 0;
}
