#include <gtest/gtest.h>

#include <string>

#include "base/mavlink/crc.h"
#include "base/mavlink/sha256.h"
#include "base/mavlink/signing.h"

namespace hitl::mavlink {
namespace {

std::span<const uint8_t> bytes(const std::string& s) { return {reinterpret_cast<const uint8_t*>(s.data()), s.size()}; }

std::string hex(std::span<const uint8_t> b) {
  static const char* digits = "0123456789abcdef";
  std::string out;
  for (uint8_t v : b) {
    out += digits[v >> 4];
    out += digits[v & 15];
  }
  return out;
}

TEST(Crc, CheckValueOfMcrf4xx) {
  // CRC-16/MCRF4XX (MAVLink's X.25 variant): the catalogue check value for "123456789".
  EXPECT_EQ(crc_x25(bytes("123456789")), 0x6F91);
}

TEST(Crc, BytewiseEqualsBulk) {
  const std::string text = "HEARTBEAT uint32_t custom_mode ";
  uint16_t crc = kX25Init;
  for (char c : text) crc = crc_accumulate(static_cast<uint8_t>(c), crc);
  EXPECT_EQ(crc, crc_x25(bytes(text)));
}

TEST(Sha256, KnownVectors) {
  Sha256 empty;
  EXPECT_EQ(hex(empty.finish()), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  Sha256 abc;
  abc.update(bytes("abc"));
  EXPECT_EQ(hex(abc.finish()), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  Sha256 two_blocks;
  two_blocks.update(bytes("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"));
  EXPECT_EQ(hex(two_blocks.finish()), "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Sha256, SplitUpdatesEqualOneUpdate) {
  std::string text(200, 'x');
  for (std::size_t i = 0; i < text.size(); ++i) text[i] = static_cast<char>('a' + i % 26);
  Sha256 one;
  one.update(bytes(text));
  Sha256 split;
  split.update(bytes(text.substr(0, 63)));
  split.update(bytes(text.substr(63, 70)));
  split.update(bytes(text.substr(133)));
  EXPECT_EQ(one.finish(), split.finish());
}

TEST(Signing, KeyFromHexOrPassphrase) {
  auto hex_key = parse_signing_key(std::string(64, 'a'));
  ASSERT_TRUE(hex_key.ok());
  EXPECT_EQ((*hex_key)[0], 0xAA);
  auto pass = parse_signing_key("secret");
  ASSERT_TRUE(pass.ok());
  Sha256 sha;
  sha.update(bytes("secret"));
  EXPECT_EQ(*pass, sha.finish());
  EXPECT_FALSE(parse_signing_key("").ok());
}

}  // namespace
}  // namespace hitl::mavlink
