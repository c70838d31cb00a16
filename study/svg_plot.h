#pragma once
/// A log-log line plot written as a standalone SVG by hand (no dependencies): used by
/// `kasumi study` for error against time.
#include <string>
#include <vector>

namespace kasumi {

struct PlotPoint {
    double x = 0.0;
    double y = 0.0;
};

/// Points joined by a line in the order given.
struct PlotSeries {
    std::string name;
    std::vector<PlotPoint> points;
};

struct LogLogPlot {
    std::string title;
    std::string x_label;
    std::string y_label;
    std::vector<PlotSeries> series;
    /// Marked with rings and joined by a dashed staircase (the Pareto front); may be empty.
    std::vector<PlotPoint> front;
    std::string front_name = "Pareto front";
};

/// The plot as an SVG document. Axes span whole decades around the data; points with x <= 0 or
/// y <= 0 (or not finite) cannot sit on log axes and are left out.
std::string svg_loglog(const LogLogPlot& plot);

/// `text` with &, <, >, " escaped for XML.
std::string xml_escape(const std::string& text);

}  // namespace kasumi
