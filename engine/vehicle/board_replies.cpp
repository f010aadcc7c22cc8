#include "engine/vehicle/board_replies.h"

#include <algorithm>
#include <cstring>

#include "base/mavlink/enums.h"
#include "base/mavlink/text_field.h"

namespace hitl::vehicle {
namespace {

constexpr uint8_t kDevShell = 10;
constexpr const char* kPrompts[] = {"pxh> ", "nsh> "};
constexpr std::size_t kPromptLen = 5;

bool ends_with_prompt(const std::string& s) {
  for (const char* prompt : kPrompts)
    if (s.size() >= kPromptLen && s.compare(s.size() - kPromptLen, kPromptLen, prompt) == 0) return true;
  return false;
}

}  // namespace

std::string param_name(const std::array<char, 16>& id) { return mavlink::text_of(id); }

ParamValue param_value_of(const mavlink::msg::ParamValue& v) {
  return decode_param_float(v.param_value, v.param_type == mavlink::kMavParamTypeInt32 ? ParamType::Int32 : ParamType::Real32);
}

bool ParamCollector::take(const mavlink::msg::ParamValue& v) {
  total_ = v.param_count;
  if (v.param_index < v.param_count && !got_.count(v.param_index)) got_[v.param_index] = Param{param_name(v.param_id), param_value_of(v)};
  return got_.size() == *total_;
}

std::vector<Param> ParamCollector::params() const {
  std::vector<Param> out;
  out.reserve(got_.size());
  for (const auto& [i, p] : got_) out.push_back(p);
  return out;
}

bool ShellOutput::append(const mavlink::msg::SerialControl& reply) {
  if (reply.device != kDevShell) return false;
  const std::size_t n = std::min<std::size_t>(reply.count, reply.data.size());
  const char* bytes = reinterpret_cast<const char*>(reply.data.data());
  const std::size_t room = kMaxShellOutputBytes - std::min(kMaxShellOutputBytes, text_.size());
  text_.append(bytes, std::min(n, room));
  cut_ = cut_ || n > room;
  tail_.append(bytes, n);
  if (tail_.size() > kPromptLen) tail_.erase(0, tail_.size() - kPromptLen);
  return ends_with_prompt(tail_);
}

void ShellOutput::clear() {
  text_.clear();
  tail_.clear();
  cut_ = false;
}

std::string ShellOutput::body() const {
  const auto first_newline = text_.find('\n');
  std::string body = first_newline == std::string::npos ? std::string() : text_.substr(first_newline + 1);
  if (ends_with_prompt(body)) body.resize(body.size() - kPromptLen);
  return body;
}

}  // namespace hitl::vehicle
