// Escaping text for XML attributes and content, shared by the VTU and XDMF writers.
#pragma once
#include <string>
#include <string_view>

namespace ugs::detail {

inline std::string xml_escape(std::string_view s) {
  std::string r;
  for (char c : s) {
    switch (c) {
      case '&': r += "&amp;"; break;
      case '<': r += "&lt;"; break;
      case '>': r += "&gt;"; break;
      case '"': r += "&quot;"; break;
      default: r += c;
    }
  }
  return r;
}

}  // namespace ugs::detail
