// Pages in headless Chromium (Debian's chromium, scripts/install-deps.sh --test): what a page's script
// did, read back from the DOM Chromium dumps. Used by the report's and the campaign page's tests.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "tests/support/tools.h"

namespace hitl::test {

/// HTML text back to text (&quot; &lt; &gt; &amp;).
inline std::string html_unescaped(std::string text) {
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{{"&quot;", "\""}, {"&lt;", "<"}, {"&gt;", ">"}, {"&amp;", "&"}}) {
    for (std::size_t at = 0; (at = text.find(from, at)) != std::string::npos; at += to.size()) text.replace(at, from.size(), to);
  }
  return text;
}

/// Chromium's path, or "" with `why_not` saying why it is missing (install-deps.sh --test installs
/// Debian's; Ubuntu has it only as a snap, which it leaves out). In CI on Debian a missing one is a
/// failure, not a skip: `required` is then set.
inline std::string find_chromium(std::string& why_not, bool& required) {
  const std::string chromium = find_program("chromium");
  required = false;
  if (!chromium.empty()) return chromium;
  const bool ubuntu = read_text("/etc/os-release").find("\nID=ubuntu") != std::string::npos;
  required = std::getenv("CI") != nullptr && !ubuntu;
  why_not = required ? "chromium is not installed (scripts/install-deps.sh --test installs it)"
                     : "chromium is not installed (Debian: scripts/install-deps.sh --test; Ubuntu: a snap, not installed for you)";
  return "";
}

/// What a page's script did in headless Chromium: the page with a probe added (an error and
/// console.error/warn catcher before every script, and after them `probe_js`, which fills `out`
/// with what it finds, r being window[page_global]), its DOM dumped; `out` as JSON (with "errors"),
/// or {"failure": why}.
inline nlohmann::json probe_in_chromium(const std::string& chromium, const std::string& html, const std::string& dir,
                                        const std::string& probe_js, const std::string& page_global = "hitlReport") {
  std::string page = read_text(html);
  const std::string catcher = R"(<script>window.hitlErrors=[];window.addEventListener('error',function(e){hitlErrors.push('error: '+e.message)});
['error','warn'].forEach(function(k){var f=console[k];console[k]=function(){hitlErrors.push(k+': '+Array.prototype.join.call(arguments,' '));f.apply(console,arguments)}});</script>)";
  const std::string probe = "<script>(function(){var out={errors:hitlErrors};try{var r=window." + page_global + ";" + probe_js +
                            "}catch(e){out.errors.push('probe: '+e)}var pre=document.createElement('pre');pre.id='hitl-probe';"
                            "pre.textContent=JSON.stringify(out);document.body.appendChild(pre)})();</script>";
  const auto head = page.find("</head>"), body = page.rfind("</body>");
  if (head == std::string::npos || body == std::string::npos) return {{"failure", "no </head> or </body> in the page"}};
  page.insert(body, probe);
  page.insert(head, catcher);
  const std::string probed = dir + "/probed.html";
  std::ofstream(probed) << page;
  auto r = run_program({chromium, "--headless", "--no-sandbox", "--disable-gpu", "--user-data-dir=" + dir + "/profile",
                        "--window-size=1200,3200", "--dump-dom", "file://" + probed},
                       std::chrono::seconds(180));
  if (r.exit_code != 0) return {{"failure", "chromium exit " + std::to_string(r.exit_code) + ": " + r.err}};
  const std::string open = "<pre id=\"hitl-probe\">";
  const auto at = r.out.find(open);
  if (at == std::string::npos) return {{"failure", "no probe in the dumped DOM (the page's script did not run to its end?)"}};
  const auto start = at + open.size();
  return nlohmann::json::parse(html_unescaped(r.out.substr(start, r.out.find("</pre>", start) - start)));
}

}  // namespace hitl::test
