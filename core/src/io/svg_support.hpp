#pragma once
// What the SVG drawings share (private to core/src/io): a small writer that appends elements to
// a buffer with coordinates in a fixed, compact precision, the node symbols of paper Fig. 3, the
// region palette and the legend layout.

#include <plmap/core/node_type.hpp>
#include <plmap/core/types.hpp>

#include <fmt/format.h>

#include <array>
#include <iterator>
#include <string>
#include <string_view>

namespace plmap::svg {

/// Light fill colours for regions: neighbouring regions map to different S2 elements, and the
/// drawings hand out these colours in order of first appearance, so neighbours differ.
inline constexpr std::array<std::string_view, 12> region_palette{
    "#f8d9a8", "#bfe0f0", "#cfe9c4", "#f4c9de", "#ddd5f3", "#fbeea0",
    "#c3e6df", "#f6cdb9", "#dcebb5", "#cfd6f6", "#efdcc6", "#bfdccd"};

/// Colour of the lines that are preimages of S2 edges, and of the node symbols.
inline constexpr std::string_view ink = "#1b1b1b";

/// Appends SVG markup to a buffer. Numbers are written with two decimals: a hundredth of a
/// pixel is far below what any renderer shows, and it keeps large drawings small.
class Writer {
 public:
  using Output = std::back_insert_iterator<fmt::memory_buffer>;

  Writer(double width, double height) {
    fmt::format_to(out(),
                   "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                   "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"{0:.0f}\" "
                   "height=\"{1:.0f}\" viewBox=\"0 0 {0:.0f} {1:.0f}\">\n",
                   width, height);
  }

  Output out() { return std::back_inserter(buffer_); }

  /// The style sheet; classes keep the per-item markup short and let users restyle a picture.
  void style(std::string_view css) {
    fmt::format_to(out(), "<style type=\"text/css\"><![CDATA[\n{}]]></style>\n", css);
  }
  void background(double width, double height, std::string_view colour = "#ffffff") {
    fmt::format_to(out(), "<rect x=\"0\" y=\"0\" width=\"{:.0f}\" height=\"{:.0f}\" fill=\"{}\"/>\n",
                   width, height, colour);
  }

  /// Text; `content` must not contain markup characters (only our own labels are written).
  void text(double x, double y, std::string_view content, std::string_view css_class,
            std::string_view anchor = "start") {
    fmt::format_to(out(), "<text class=\"{}\" x=\"{:.2f}\" y=\"{:.2f}\" text-anchor=\"{}\">{}</text>\n",
                   css_class, x, y, anchor, escaped(content));
  }
  void line(double x0, double y0, double x1, double y1, std::string_view css_class,
            std::string_view extra = {}) {
    fmt::format_to(out(), "<line class=\"{}\" x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\"{}/>\n",
                   css_class, x0, y0, x1, y1, extra);
  }
  void rect(double x, double y, double w, double h, std::string_view css_class,
            std::string_view extra = {}) {
    fmt::format_to(out(), "<rect class=\"{}\" x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\"{}/>\n",
                   css_class, x, y, w, h, extra);
  }

  /// The symbol of a node of type `type` centred at (x, y), as in paper Fig. 3: corner filled
  /// disc, touching open square, intersection filled diamond (a filled square would be hard to
  /// tell from the open one at small sizes), ghost open circle, interior small dot.
  void node_symbol(NodeType type, double x, double y, double radius, std::string_view extra = {}) {
    const std::string_view name = to_string(type);
    switch (type) {
      case NodeType::corner:
      case NodeType::ghost:
        fmt::format_to(out(), "<circle class=\"node {}\" cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{:.2f}\"{}/>\n",
                       name, x, y, radius, extra);
        return;
      case NodeType::interior:
        fmt::format_to(out(), "<circle class=\"node {}\" cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"{:.2f}\"{}/>\n",
                       name, x, y, 0.55 * radius, extra);
        return;
      case NodeType::touching: {
        const double h = 0.85 * radius;
        fmt::format_to(out(), "<rect class=\"node {}\" x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\"{}/>\n",
                       name, x - h, y - h, 2 * h, 2 * h, extra);
        return;
      }
      case NodeType::intersection: {
        const double h = 1.2 * radius;
        fmt::format_to(out(), "<path class=\"node {}\" d=\"M{:.2f} {:.2f}L{:.2f} {:.2f}L{:.2f} {:.2f}L{:.2f} {:.2f}Z\"{}/>\n",
                       name, x, y - h, x + h, y, x, y + h, x - h, y, extra);
        return;
      }      case NodeType::rim_on_edge:
      case NodeType::rim_inside: {
        // a triangle pointing up: the map stops here (larger on an S1 edge)
        const double h = (type == NodeType::rim_on_edge ? 1.2 : 0.8) * radius;
        fmt::format_to(out(), "<path class=\"node {}\" d=\"M{:.2f} {:.2f}L{:.2f} {:.2f}L{:.2f} {:.2f}Z\"{}/>\n",
                       name, x, y - h, x + h, y + h, x - h, y + h, extra);
        return;
      }
    }
  }

  /// Raw markup (used for paths assembled by the caller).
  void raw(std::string_view markup) { buffer_.append(markup); }

  std::string finish() {
    buffer_.append(std::string_view("</svg>\n"));
    return fmt::to_string(buffer_);
  }

 private:
  static std::string escaped(std::string_view s) {
    std::string r;
    r.reserve(s.size());
    for (char c : s) {
      switch (c) {
        case '<': r += "&lt;"; break;
        case '>': r += "&gt;"; break;
        case '&': r += "&amp;"; break;
        case '"': r += "&quot;"; break;
        default: r += c;
      }
    }
    return r;
  }

  fmt::memory_buffer buffer_;
};

/// CSS for the node symbols, shared by the element picture and the d = 1 view.
inline constexpr std::string_view node_css =
    ".node{stroke:#1b1b1b;stroke-width:1.6}\n"
    ".node.corner,.node.interior,.node.intersection{fill:#1b1b1b}\n"
    ".node.interior{stroke:none}\n"
    ".node.touching,.node.ghost{fill:#ffffff}\n"
    ".label{font-family:'DejaVu Sans',Arial,Helvetica,sans-serif;font-size:12px;fill:#1b1b1b}\n"
    ".small{font-size:10px;fill:#444444}\n"
    ".title{font-family:'DejaVu Sans',Arial,Helvetica,sans-serif;font-size:14px;"
    "font-weight:bold;fill:#1b1b1b}\n"
    ".legend-box{fill:#ffffff;stroke:#b0b0b0;stroke-width:1}\n";

/// One-line description of each node type for legends.
constexpr std::string_view node_type_description(NodeType t) {
  switch (t) {
    case NodeType::corner: return "corner: S2 vertex at an S1 corner";
    case NodeType::touching: return "touching: S2 vertex on an S1 edge";
    case NodeType::intersection: return "intersection: S2 edge crosses S1 edge";
    case NodeType::ghost: return "ghost: S1 corner, no S2 vertex";
    case NodeType::interior: return "interior: S2 vertex inside";
    case NodeType::rim_on_edge: return "rim on edge: D ends, crossing an S1 edge";
    case NodeType::rim_inside: return "rim inside: D ends inside";
  }
  return "";
}

}  // namespace plmap::svg
