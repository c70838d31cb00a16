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

bool plottable(const PlotPoint& p) {
    return std::isfinite(p.x) && std::isfinite(p.y) && p.x > 0.0 && p.y > 0.0;
}

struct Decades {
    int lo = 0, hi = 1;
};

Decades decades(double lo, double hi) {
    Decades d{static_cast<int>(std::floor(std::log10(lo))),
              static_cast<int>(std::ceil(std::log10(hi)))};
    if (d.hi <= d.lo)
        d.hi = d.lo + 1;
    return d;
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

std::string svg_loglog(const LogLogPlot& plot) {
    double x_lo = INFINITY, x_hi = -INFINITY, y_lo = INFINITY, y_hi = -INFINITY;
    for (const PlotSeries& s : plot.series) {
        for (const PlotPoint& p : s.points) {
            if (!plottable(p))
                continue;
            x_lo = std::min(x_lo, p.x);
            x_hi = std::max(x_hi, p.x);
            y_lo = std::min(y_lo, p.y);
            y_hi = std::max(y_hi, p.y);
        }
    }
    if (!(x_lo <= x_hi)) {
        x_lo = y_lo = 1.0;
        x_hi = y_hi = 10.0;
    }
    const Decades dx = decades(x_lo, x_hi), dy = decades(y_lo, y_hi);
    const double plot_w = kWidth - kLeft - kRight, plot_h = kHeight - kTop - kBottom;
    auto sx = [&](double x) { return kLeft + (std::log10(x) - dx.lo) / (dx.hi - dx.lo) * plot_w; };
    auto sy = [&](double y) {
        return kTop + plot_h - (std::log10(y) - dy.lo) / (dy.hi - dy.lo) * plot_h;
    };

    std::ostringstream svg;
    svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << kWidth << "\" height=\""
        << kHeight << "\" viewBox=\"0 0 " << kWidth << " " << kHeight
        << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
    svg << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
    svg << "<text x=\"" << kLeft + plot_w / 2 << "\" y=\"22\" text-anchor=\"middle\" "
        << "font-size=\"14\">" << xml_escape(plot.title) << "</text>\n";

    // Grid: decades solid, 2..9 faint.
    for (int e = dx.lo; e <= dx.hi; ++e) {
        for (int m = 1; m <= 9 && (m == 1 || e < dx.hi); ++m) {
            const double x = sx(m * std::pow(10.0, e));
            svg << "<line x1=\"" << number(x) << "\" y1=\"" << kTop << "\" x2=\"" << number(x)
                << "\" y2=\"" << kTop + plot_h << "\" stroke=\"" << (m == 1 ? "#bbb" : "#eee")
                << "\"/>\n";
        }
        svg << "<text x=\"" << number(sx(std::pow(10.0, e))) << "\" y=\"" << kTop + plot_h + 18
            << "\" text-anchor=\"middle\">" << decade_label(e) << "</text>\n";
    }
    for (int e = dy.lo; e <= dy.hi; ++e) {
        for (int m = 1; m <= 9 && (m == 1 || e < dy.hi); ++m) {
            const double y = sy(m * std::pow(10.0, e));
            svg << "<line x1=\"" << kLeft << "\" y1=\"" << number(y) << "\" x2=\"" << kLeft + plot_w
                << "\" y2=\"" << number(y) << "\" stroke=\"" << (m == 1 ? "#bbb" : "#eee")
                << "\"/>\n";
        }
        svg << "<text x=\"" << kLeft - 6 << "\" y=\"" << number(sy(std::pow(10.0, e)) + 4)
            << "\" text-anchor=\"end\">" << decade_label(e) << "</text>\n";
    }
    svg << "<rect x=\"" << kLeft << "\" y=\"" << kTop << "\" width=\"" << plot_w << "\" height=\""
        << plot_h << "\" fill=\"none\" stroke=\"#333\"/>\n";
    svg << "<text x=\"" << kLeft + plot_w / 2 << "\" y=\"" << kHeight - 18
        << "\" text-anchor=\"middle\">" << xml_escape(plot.x_label) << "</text>\n";
    svg << "<text transform=\"translate(20," << kTop + plot_h / 2
        << ") rotate(-90)\" text-anchor=\"middle\">" << xml_escape(plot.y_label) << "</text>\n";

    // Pareto front below the series: a dashed staircase through the front's points.
    std::vector<PlotPoint> front;
    for (const PlotPoint& p : plot.front) {
        if (plottable(p))
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
            if (plottable(p))
                svg << number(sx(p.x)) << "," << number(sy(p.y)) << " ";
        }
        svg << "\"/>\n";
        for (const PlotPoint& p : s.points) {
            if (plottable(p)) {
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
