// Offline HTML pages for the reports: escaping and the page frame (viz.hpp).
#include <string>

#include "ptnet/viz.hpp"

namespace ptnet {
namespace {

// One style for every report page: readable tables, figures scaled to the column.
constexpr const char* kStyle = R"css(
body { font-family: sans-serif; margin: 24px auto; max-width: 1240px; padding: 0 16px; color: #1a1a1a; }
h1 { font-size: 24px; } h2 { font-size: 19px; margin-top: 36px; border-bottom: 1px solid #ddd; }
h3 { font-size: 16px; }
p.note, .note { color: #555; font-size: 13px; }
p.warning { background: #fff4e0; border-left: 4px solid #d55e00; padding: 6px 10px; }
table { border-collapse: collapse; margin: 8px 0 16px; font-size: 13px; }
th, td { border: 1px solid #ccc; padding: 3px 8px; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
th { background: #f2f2f2; } tr.section th { text-align: left; background: #e6eef6; }
tr.average td { font-weight: bold; }
td.best { background: #e3f4e3; } td.paper { color: #666; }
.charts { display: flex; flex-wrap: wrap; gap: 12px; }
.charts img { border: 1px solid #eee; }
figure { margin: 12px 0 28px; } figcaption { font-size: 13px; color: #444; margin-bottom: 6px; }
figure .pair { display: flex; flex-wrap: wrap; gap: 16px; align-items: flex-start; }
figure img.still, figure img.anim { max-width: 100%; height: auto; border: 1px solid #eee; }
img { image-rendering: pixelated; } .charts img { image-rendering: auto; }
pre { background: #f7f7f7; padding: 8px; font-size: 12px; overflow-x: auto; max-height: 420px; }
)css";

// The browser test reads body[data-ok] and body[data-failures].
constexpr const char* kCheckScript = R"js(
(function () {
  var failures = [];
  window.addEventListener('error', function (e) {
    var t = e.target;
    failures.push(t && t.tagName ? 'cannot load ' + (t.getAttribute('src') || t.tagName) : 'script error: ' + e.message);
  }, true);
  window.addEventListener('load', function () {
    var images = document.getElementsByTagName('img');
    for (var i = 0; i < images.length; ++i)
      if (!images[i].complete || images[i].naturalWidth === 0)
        failures.push('broken image ' + images[i].getAttribute('src'));
    document.body.dataset.images = String(images.length);
    document.body.dataset.failures = failures.join('; ');
    document.body.dataset.ok = failures.length ? 'no' : 'yes';
  });
})();
)js";

}  // namespace

std::string html_escape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  return out;
}

std::string html_page(const std::string& title, const std::string& body_html) {
  return std::string("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n") +
         "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>" +
         html_escape(title) + "</title>\n<style>" + kStyle + "</style>\n<script>" + kCheckScript +
         "</script>\n</head>\n<body>\n" + body_html + "\n<p class=\"note\">Written by ptnet " +
         PTNET_VERSION +
         "; works offline: every image is a file beside this page.</p>\n</body>\n</html>\n";
}

}  // namespace ptnet
