#include "study/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace kasumi {

namespace {

constexpr double kWidth = 760.0, kHeight = 480.0;
constexpr double kLeft = 80.0, kRight = 220.0, kTop = 40.0, kBottom = 60.0;

// Colour-blind-safe qualitative palette (Okabe & Ito 2008).
constexpr const char* kPalette[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                    "#E69F00", "#56B4E9", "#F0E442", "#000000"};

bool on_axis(const PlotAxis& axis, double v) {
    if (!std::isfinite(v))
        return false;
    return axis.scale == AxisScale::Linear || v > 0.0 || axis.max_decades > 0;
}

bool plottable(const LinePlot& plot, const PlotPoint& p) {
    return on_axis(plot.x, p.x) && on_axis(plot.y, p.y);
}

/// An axis fitted to the data: [lo, hi] in values (linear) or in decades (log), and where a
/// value lands on it as a fraction of its length.
struct AxisRange {
    const PlotAxis* axis = nullptr;
    double lo = 0.0, hi = 1.0;
    double floor_value = 0.0;  ///< log with max_decades: smaller values are drawn here

    double fraction(double v) const {
        if (axis->scale == AxisScale::Linear)
            return (v - lo) / (hi - lo);
        return (std::log10(std::max(v, floor_value)) - lo) / (hi - lo);
    }
};

/// `data_lo`, `data_hi`: the smallest and largest value > 0 on a log axis (lo > hi if none).
AxisRange fit(const PlotAxis& axis, double data_lo, double data_hi) {
    AxisRange r;
    r.axis = &axis;
    if (axis.scale == AxisScale::Linear) {
        r.lo = axis.lo;
        r.hi = axis.hi;
        return r;
    }
    if (!(data_lo <= data_hi)) {
        data_lo = 1.0;
        data_hi = 10.0;
    }
    int lo = static_cast<int>(std::floor(std::log10(data_lo)));
    int hi = static_cast<int>(std::ceil(std::log10(data_hi)));
    if (hi <= lo)
        hi = lo + 1;
    if (axis.max_decades > 0)
        lo = std::max(lo, hi - axis.max_decades);
    r.lo = lo;
    r.hi = hi;
    r.floor_value = std::pow(10.0, lo);
    return r;
}

std::string number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f", v);
    return buf;
}

std::string decade_label(int e) {
    if (e >= -2 && e <= 3) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", std::pow(10.0, e));
        return buf;
    }
    return "1e" + std::to_string(e);
}

std::string linear_label(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

/// A grid line of an axis: its value, whether it is labelled (and solid), and its label.
struct GridLine {
    double value = 0.0;
    bool major = false;
    std::string label;
};

/// Log: decades solid and labelled, 2..9 faint. Linear: every step, labelled.
std::vector<GridLine> grid_lines(const AxisRange& r) {
    std::vector<GridLine> lines;
    if (r.axis->scale == AxisScale::Linear) {
        const double step = r.axis->step;
        // Counted, not accumulated, so the last line lands on hi exactly.
        const int n = step > 0.0 ? static_cast<int>(std::floor((r.hi - r.lo) / step + 1e-9)) : 0;
        for (int i = 0; i <= n; ++i) {
            const double v = r.lo + step * i;
            lines.push_back({v, true, linear_label(v)});
        }
        return lines;
    }
    const int lo = static_cast<int>(r.lo), hi = static_cast<int>(r.hi);
    for (int e = lo; e <= hi; ++e) {
        for (int m = 1; m <= 9 && (m == 1 || e < hi); ++m)
            lines.push_back({m * std::pow(10.0, e), m == 1, m == 1 ? decade_label(e) : ""});
    }
    return lines;
}

}  // namespace

std::string xml_escape(const std::string& text) {
    std::string out;
    for (char c : text) {
        switch (c) {
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
            default:
                out += c;
        }
    }
    return out;
}

std::string svg_line_plot(const LinePlot& plot) {
    double x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
    for (const PlotSeries& s : plot.series) {
        for (const PlotPoint& p : s.points) {
            if (!plottable(plot, p))
                continue;
            if (p.x > 0.0) {
                x_lo = std::min(x_lo, p.x);
                x_hi = std::max(x_hi, p.x);
            }
            if (p.y > 0.0) {
                y_lo = std::min(y_lo, p.y);
                y_hi = std::max(y_hi, p.y);
            }
        }
    }
    const AxisRange rx = fit(plot.x, x_lo, x_hi), ry = fit(plot.y, y_lo, y_hi);
    const double plot_w = kWidth - kLeft - kRight, plot_h = kHeight - kTop - kBottom;
    auto sx = [&](double x) { return kLeft + rx.fraction(x) * plot_w; };
    auto sy = [&](double y) { return kTop + plot_h - ry.fraction(y) * plot_h; };

    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\""
        << kHeight << "\" viewBox=\"0 0 " << kWidth << " " << kHeight
        << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
    svg << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    if (!plot.title.empty()) {
        svg << "<text x=\"" << kLeft + plot_w / 2 << "\" y=\"22\" text-anchor=\"middle\" "
            << "font-size=\"14\">" << xml_escape(plot.title) << "</text>\n";
    }

    // Each decade's label after its faint lines (pending until the next decade starts).
    std::ostringstream label;
    const auto flush_label = [&] {
        svg << label.str();
        label.str("");
    };
    for (const GridLine& g : grid_lines(rx)) {
        const double x = sx(g.value);
        if (g.major) {
            flush_label();
            label << "<text x=\"" << number(x) << "\" y=\"" << kTop + plot_h + 18
                  << "\" text-anchor=\"middle\">" << g.label << "</text>\n";
        }
        svg << "<line x1=\"" << number(x) << "\" y1=\"" << kTop << "\" x2=\"" << number(x)
            << "\" y2=\"" << kTop + plot_h << "\" stroke=\"" << (g.major ? "#bbb" : "#eee")
            << "\"/>\n";
    }
    flush_label();
    for (const GridLine& g : grid_lines(ry)) {
        const double y = sy(g.value);
        if (g.major) {
            flush_label();
            label << "<text x=\"" << kLeft - 6 << "\" y=\"" << number(y + 4)
                  << "\" text-anchor=\"end\">" << g.label << "</text>\n";
        }
        svg << "<line x1=\"" << kLeft << "\" y1=\"" << number(y) << "\" x2=\"" << kLeft + plot_w
            << "\" y2=\"" << number(y) << "\" stroke=\"" << (g.major ? "#bbb" : "#eee") << "\"/>\n";
    }
    flush_label();
    svg << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << plot_w << "\" height=\""
        << plot_h << "\" fill=\"none\" stroke=\"#333\"/>\n";
    svg << "<text x=\"" << kLeft + plot_w / 2 << "\" y=\"" << kHeight - 18
        << "\" text-anchor=\"middle\">" << xml_escape(plot.x.label) << "</text>\n";
    svg << "<text transform=\"translate(20," << kTop + plot_h / 2
        << ") rotate(-90)\" text-anchor=\"middle\">" << xml_escape(plot.y.label) << "</text>\n";

    // Pareto front below the series: a dashed staircase through the front's points.
    std::vector<PlotPoint> front;
    for (const PlotPoint& p : plot.front) {
        if (plottable(plot, p))
            front.push_back(p);
    }
    std::sort(front.begin(), front.end(),
              [](const PlotPoint& a, const PlotPoint& b) { return a.x < b.x; });
    if (front.size() > 1) {
        svg << "<polyline fill=\"none\" stroke=\"#444\" stroke-dasharray=\"5,4\" points=\"";
        for (size_t i = 0; i < front.size(); ++i) {
            if (i > 0)
                svg << number(sx(front[i].x)) << "," << number(sy(front[i - 1].y)) << " ";
            svg << number(sx(front[i].x)) << "," << number(sy(front[i].y)) << " ";
        }
        svg << "\"/>\n";
    }

    double legend_y = kTop + 10;
    const double legend_x = kLeft + plot_w + 16;
    for (size_t k = 0; k < plot.series.size(); ++k) {
        const PlotSeries& s = plot.series[k];
        const char* colour = kPalette[k % (sizeof kPalette / sizeof kPalette[0])];
        svg << "<polyline fill=\"none\" stroke=\"" << colour << "\" stroke-width=\"1.5\" points=\"";
        for (const PlotPoint& p : s.points) {
            if (plottable(plot, p))
                svg << number(sx(p.x)) << "," << number(sy(p.y)) << " ";
        }
        svg << "\"/>\n";
        for (const PlotPoint& p : s.points) {
            if (s.markers && plottable(plot, p)) {
                svg << "<circle cx=\"" << number(sx(p.x)) << "\" cy=\"" << number(sy(p.y))
                    << "\" r=\"3\" fill=\"" << colour << "\"/>\n";
            }
        }
        svg << "<line x1=\"" << legend_x << "\" y1=\"" << legend_y << "\" x2=\"" << legend_x + 18
            << "\" y2=\"" << legend_y << "\" stroke=\"" << colour << "\" stroke-width=\"2\"/>\n";
        svg << "<text x=\"" << legend_x + 24 << "\" y=\"" << legend_y + 4 << "\">"
            << xml_escape(s.name) << "</text>\n";
        legend_y += 18;
    }
    for (const PlotPoint& p : front) {
        svg << "<circle cx=\"" << number(sx(p.x)) << "\" cy=\"" << number(sy(p.y))
            << "\" r=\"7\" fill=\"none\" stroke=\"#000\" stroke-width=\"1.5\"/>\n";
    }
    if (!front.empty()) {
        svg << "<circle cx=\"" << legend_x + 9 << "\" cy=\"" << legend_y << "\" r=\"6\" "
            << "fill=\"none\" stroke=\"#000\" stroke-width=\"1.5\"/>\n";
        svg << "<text x=\"" << legend_x + 24 << "\" y=\"" << legend_y + 4 << "\">"
            << xml_escape(plot.front_name) << "</text>\n";
    }
    svg << "</svg>\n";
    return svg.str();
}

}  // namespace kasumi
