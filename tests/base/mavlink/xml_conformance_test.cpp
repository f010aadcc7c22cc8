// Conformance (a): every compiled-in message against the official MAVLink XML in
// ../shared/mavlink: id, CRC_EXTRA, wire order, types, array lengths, extensions.
// Skips, saying so, when that folder is absent (the build never needs it).
#include <gtest/gtest.h>

#include <pugixml.hpp>

#include <filesystem>
#include <map>

#include "base/mavlink/messages.h"
#include "base/mavlink/typed_codec.h"
#include "engine/mavlink/dialect_xml.h"

namespace hitl::mavlink {
namespace {

const std::string kXmlDir = HITL_MAVLINK_XML_DIR;

struct XmlField {
  std::string type;  // as written, e.g. "float[4]", "uint8_t_mavlink_version"
  bool extension;
};

// The XML's own field list for one message, read directly (no wire-order logic).
std::map<std::string, std::vector<std::pair<std::string, XmlField>>> read_raw(const std::string& dir) {
  std::map<std::string, std::vector<std::pair<std::string, XmlField>>> out;
  for (const char* file : {"minimal.xml", "standard.xml", "common.xml", "development.xml"}) {
    pugi::xml_document doc;
    if (!doc.load_file((dir + "/" + file).c_str())) continue;
    for (const auto& m : doc.child("mavlink").child("messages").children("message")) {
      auto& fields = out[m.attribute("name").as_string()];
      fields.clear();
      bool ext = false;
      for (const auto& c : m.children()) {
        if (std::string(c.name()) == "extensions") ext = true;
        if (std::string(c.name()) == "field") fields.push_back({c.attribute("name").as_string(), {c.attribute("type").as_string(), ext}});
      }
    }
  }
  return out;
}

std::string type_text(const FieldDesc& f) {
  std::string t(to_string(f.type));
  if (f.array_length) t += "[" + std::to_string(f.array_length) + "]";
  return t;
}

class XmlConformance : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!std::filesystem::exists(kXmlDir + "/development.xml"))
      GTEST_SKIP() << "official MAVLink XML not found at " << kXmlDir << " (set HITL_MAVLINK_XML_DIR); skipping";
    auto info = load_dialect(kXmlDir + "/development.xml", from_xml_);
    ASSERT_TRUE(info.ok()) << info.error().message;
    raw_ = read_raw(kXmlDir);
  }
  MessageSet from_xml_;
  std::map<std::string, std::vector<std::pair<std::string, XmlField>>> raw_;
};

template <class M>
void check(const MessageSet& from_xml, const std::map<std::string, std::vector<std::pair<std::string, XmlField>>>& raw) {
  SCOPED_TRACE(std::string(M::kName));
  const MessageDesc compiled = describe<M>();
  const MessageDesc* xml = from_xml.find(compiled.name);
  ASSERT_NE(xml, nullptr) << "not in the XML";
  EXPECT_EQ(xml->id, compiled.id);
  EXPECT_EQ(xml->crc_extra, compiled.crc_extra);
  EXPECT_EQ(xml->min_length, compiled.min_length);
  EXPECT_EQ(xml->max_length, compiled.max_length);
  ASSERT_EQ(xml->fields.size(), compiled.fields.size());
  for (std::size_t i = 0; i < compiled.fields.size(); ++i) {
    EXPECT_EQ(xml->fields[i].name, compiled.fields[i].name) << "wire position " << i;
    EXPECT_EQ(xml->fields[i].offset, compiled.fields[i].offset) << compiled.fields[i].name;
  }
  // Against the raw XML: same fields with the same types and extension flags.
  const auto& raw_fields = raw.at(compiled.name);
  ASSERT_EQ(raw_fields.size(), compiled.fields.size());
  for (const auto& [name, xf] : raw_fields) {
    const FieldDesc* f = compiled.field(name);
    ASSERT_NE(f, nullptr) << "field " << name << " missing from the compiled message";
    std::string xml_type = xf.type == "uint8_t_mavlink_version" ? "uint8_t" : xf.type;
    EXPECT_EQ(type_text(*f), xml_type) << name;
    EXPECT_EQ(f->extension, xf.extension) << name;
  }
}

template <class... Ms>
void check_all(const MessageSet& from_xml, const auto& raw, TypeList<Ms...>) {
  (check<Ms>(from_xml, raw), ...);
}

TEST_F(XmlConformance, EveryCompiledMessageMatchesTheOfficialDefinition) { check_all(from_xml_, raw_, msg::All{}); }

// The generated table of every message (message_check.h) against the XML as the dialect loader reads it.
TEST_F(XmlConformance, EveryMessageOfTheXmlIsInTheCheckTable) {
  EXPECT_EQ(msg::kStandardChecks.size(), from_xml_.size());
  for (const MessageDesc* xml : from_xml_.all()) {
    SCOPED_TRACE(xml->name);
    const MessageCheck* c = find_standard_check(xml->id);
    ASSERT_NE(c, nullptr);
    EXPECT_EQ(c->crc_extra, xml->crc_extra);
    EXPECT_EQ(c->min_length, xml->min_length);
    EXPECT_EQ(c->max_length, xml->max_length);
    const FieldDesc* system = xml->field("target_system");
    if (system == nullptr) system = xml->field("target");
    const FieldDesc* component = xml->field("target_component");
    EXPECT_EQ((c->flags & MessageCheck::kHasTargetSystem) != 0, system != nullptr);
    EXPECT_EQ((c->flags & MessageCheck::kHasTargetComponent) != 0, component != nullptr);
    if (system != nullptr) {
      EXPECT_EQ(c->target_system_offset, system->offset);
    }
    if (component != nullptr) {
      EXPECT_EQ(c->target_component_offset, component->offset);
    }
  }
}

TEST_F(XmlConformance, TheWholeDialectLoadsWithPlausibleCrcExtras) {
  EXPECT_GT(from_xml_.size(), 200u);
  EXPECT_EQ(from_xml_.find("HEARTBEAT")->crc_extra, 50);
}

}  // namespace
}  // namespace hitl::mavlink
