#include "engine/mavlink/statustext.h"

#include <algorithm>
#include <tuple>

#include "base/mavlink/text_field.h"

namespace hitl::mavlink {
namespace {

constexpr const char* kMissing = "[ missing ... ]";

bool ends_text(const msg::Statustext& chunk) {
  return std::find(chunk.text.begin(), chunk.text.end(), '\0') != chunk.text.end();
}

}  // namespace

std::vector<StatusText> StatusTextAssembler::on_frame(const Frame& frame, double now_s) {
  if (!frame.is<msg::Statustext>()) return {};
  return on_statustext(frame.sysid, frame.compid, frame.as<msg::Statustext>(), now_s);
}

std::vector<StatusText> StatusTextAssembler::on_statustext(uint8_t sysid, uint8_t compid, const msg::Statustext& chunk,
                                                           double now_s) {
  std::vector<StatusText> out = expire(now_s);
  // One text open per source: a sender finishes a text before it starts the next, so a chunk of
  // another id, or one that does not follow, closes what the source had open (a text that filled
  // its last chunk exactly has no closing chunk: it is complete, not cut).
  auto it = std::find_if(pending_.begin(), pending_.end(),
                         [&](const Pending& p) { return p.text.sysid == sysid && p.text.compid == compid; });
  if (it != pending_.end() && (it->id != chunk.id || chunk.chunk_seq <= it->last_chunk_seq)) {
    out.push_back(std::move(it->text));
    pending_.erase(it);
    it = pending_.end();
  }
  if (it == pending_.end()) {
    if (pending_.size() >= kMaxPending) {  // the longest waiting goes out as it is
      auto oldest = std::min_element(pending_.begin(), pending_.end(),
                                     [](const Pending& a, const Pending& b) { return a.last_chunk_s < b.last_chunk_s; });
      out.push_back(std::move(oldest->text));
      pending_.erase(oldest);
    }
    Pending p;
    p.text.sysid = sysid;
    p.text.compid = compid;
    p.text.severity = chunk.severity;
    p.text.first_chunk_s = now_s;
    p.id = chunk.id;
    p.last_chunk_seq = -1;
    pending_.push_back(std::move(p));
    it = pending_.end() - 1;
  }
  if (chunk.chunk_seq != it->last_chunk_seq + 1) {  // the first chunks, or some between, never came
    it->text.text += kMissing;
    it->text.incomplete = true;
  }
  it->text.text += text_of(chunk.text);
  it->text.chunks += 1;
  it->last_chunk_seq = chunk.chunk_seq;
  it->last_chunk_s = now_s;
  const bool last = ends_text(chunk);
  if (last || it->text.chunks >= kMaxChunks) {
    it->text.incomplete = it->text.incomplete || !last;
    out.push_back(std::move(it->text));
    pending_.erase(it);
  }
  return out;
}

std::vector<StatusText> StatusTextAssembler::expire(double now_s) {
  std::vector<StatusText> out;
  for (auto p = pending_.begin(); p != pending_.end();) {
    if (now_s - p->last_chunk_s >= kChunkWait_s) {
      out.push_back(std::move(p->text));
      p = pending_.erase(p);
    } else {
      ++p;
    }
  }
  return out;
}

std::vector<StatusText> StatusTextAssembler::flush() {
  std::vector<StatusText> out;
  for (auto& p : pending_) out.push_back(std::move(p.text));
  pending_.clear();
  return out;
}

std::vector<msg::Statustext> StatusTextChunker::split(uint8_t severity, std::string_view text) {
  constexpr std::size_t kChunk = std::tuple_size_v<decltype(msg::Statustext::text)>;
  text = text.substr(0, std::min(text.size(), kChunk * StatusTextAssembler::kMaxChunks));
  std::vector<msg::Statustext> out;
  const bool several = text.size() > kChunk;
  const uint16_t id = several ? next_id_ : 0;
  if (several && ++next_id_ == 0) next_id_ = 1;
  uint8_t seq = 0;
  do {
    msg::Statustext st;
    st.severity = severity;
    st.id = id;
    st.chunk_seq = seq++;
    set_text(st.text, text.substr(0, std::min(text.size(), kChunk)));
    out.push_back(st);
    text.remove_prefix(std::min(text.size(), kChunk));
  } while (!text.empty());
  return out;
}

std::string printable_statustext(const std::string& text) {
  std::string out = text;
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7F) c = ' ';
  return out;
}

}  // namespace hitl::mavlink
