#pragma once
/// A line plot written as a standalone SVG by hand (no dependencies), each axis logarithmic or
/// linear: used by `kasumi study` (error against time, log-log) and `kasumi phase plot` (p(θ)
/// against θ, log-linear).
#include <string>
#include <vector>

namespace kasumi {

struct PlotPoint {
    double x = 0.0;
    double y = 0.0;
};

/// Points joined by a line in the order given, each marked with a dot when `markers`.
struct PlotSeries {
    std::string name;
    std::vector<PlotPoint> points;
    bool markers = true;
};

/// How an axis maps values to the page.
enum class AxisScale {
    Log,     ///< whole decades around the data, each labelled, 2..9 as faint lines
    Linear,  ///< [lo, hi] with a labelled line every `step`
};

struct PlotAxis {
    std::string label;
    AxisScale scale = AxisScale::Log;
    /// Linear only: the range shown and the spacing of its labelled lines (step > 0).
    double lo = 0.0, hi = 1.0, step = 1.0;
    /// Log only, when > 0: at most this many decades below the top one; smaller values (zero
    /// included) sit on the bottom line instead of being left out.
    int max_decades = 0;
};

struct LinePlot {
    std::string title;  ///< none drawn when empty
    PlotAxis x, y;
    std::vector<PlotSeries> series;
    /// Marked with rings and joined by a dashed staircase (the Pareto front); may be empty.
    std::vector<PlotPoint> front;
    std::string front_name = "Pareto front";
};

/// The plot as an SVG document with a legend naming every series right of the axes. Points
/// that cannot sit on an axis (not finite; <= 0 on a log axis unless max_decades clamps them)
/// are left out.
std::string svg_line_plot(const LinePlot& plot);

/// `text` with &, <, >, " escaped for XML.
std::string xml_escape(const std::string& text);

}  // namespace kasumi
