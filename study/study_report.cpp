#include "study/study_report.h"

#include "core/atomic_file.h"
#include "core/error.h"
#include "study/svg_plot.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

namespace kasumi {

namespace {

std::string g3(double v) {
    if (std::isinf(v))
        return "inf";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", v);
    return buf;
}

std::string signed_percent(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%+.2g%%", 100.0 * v);
    return buf;
}

std::string csv_field(const std::string& text) {
    if (text.find_first_of(",\"\n") == std::string::npos)
        return text;
    std::string out = "\"";
    for (char c : text)
        out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
}

std::string word(const std::string& value) {
    if (value.size() >= 2 && value.front() == '"' && value.back() == '"')
        return value.substr(1, value.size() - 2);
    return value;
}

/// Members of a JSON object as "key=value" joined by ", ", nested objects as "a.b=value".
void flatten(const Json& object, const std::string& prefix, std::string& out) {
    for (auto it = object.begin(); it != object.end(); ++it) {
        const std::string key = prefix + it.key();
        if (it.value().is_object() && !it.value().empty()) {
            flatten(it.value(), key + ".", out);
            continue;
        }
        out += (out.empty() ? "" : ", ") + key + "=" +
               (it.value().is_string() ? it.value().get<std::string>() : it.value().dump());
    }
}

/// A value as shown in tables and legends: strings without quotes, a merged object as its
/// flattened members ("shadows=map, shadow_map.resolution=512").
std::string shown(const std::string& value) {
    if (!value.empty() && value.front() == '{') {
        try {
            const Json j = Json::parse(value);
            if (j.is_object()) {
                std::string out;
                flatten(j, "", out);
                return out.empty() ? "{}" : out;
            }
        } catch (const Json::exception&) {
        }
    }
    return word(value);
}

/// An axis key as a legend names it: its last token, or the whole key if that is '*'.
std::string short_key(const std::string& key) {
    const std::string last = key.substr(key.rfind('/') + 1);
    return last == "*" ? key : last;
}

bool has_spp_axis(const StudyResult& r) {
    for (const StudyAxis& a : r.axes) {
        if (a.key == "spp")
            return true;
    }
    return false;
}

size_t best_efficiency(const StudyResult& r) {
    size_t best = 0;
    for (size_t i = 1; i < r.rows.size(); ++i) {
        if (r.rows[i].efficiency > r.rows[best].efficiency)
            best = i;
    }
    return best;
}

}  // namespace

std::string study_csv(const StudyResult& result) {
    std::ostringstream out;
    for (const StudyAxis& a : result.axes)
        out << csv_field(a.key) << ",";
    out << "film_spp,median_seconds,min_seconds,max_seconds,repeats,rmse,rel_mse,max_rel_luminance,"
           "mean_luminance_error,efficiency,pareto\n";
    char buf[64];
    auto num = [&](double v) {
        std::snprintf(buf, sizeof buf, "%.6g", v);
        return std::string(buf);
    };
    for (const StudyRow& row : result.rows) {
        for (const std::string& v : row.values)
            out << csv_field(word(v)) << ",";
        double lo = INFINITY, hi = 0.0;
        for (double s : row.seconds) {
            lo = std::min(lo, s);
            hi = std::max(hi, s);
        }
        out << row.spp << "," << num(row.median_seconds) << "," << num(lo) << "," << num(hi) << ","
            << row.seconds.size() << "," << num(row.error.rmse) << "," << num(row.error.rel_mse)
            << "," << num(row.error.max_rel_luminance) << "," << num(row.error.mean_luminance_error)
            << "," << num(row.efficiency) << "," << (row.pareto ? 1 : 0) << "\n";
    }
    return out.str();
}

std::string study_markdown(const StudyResult& result) {
    std::ostringstream out;
    const ErrorSettings& e = result.error;
    out << "# Study of `" << result.scene << "`\n\n";
    if (result.probe.empty())
        out << result.width << "x" << result.height << " pixels; time: median render time of ";
    else
        out << "Probe: " << result.probe << " (spp: samples averaged); time: median probe time of ";
    out << (result.rows.empty() ? 0 : result.rows[0].seconds.size())
        << (result.timing == StudyTiming::BuildRender
                ? " interleaved repeats, each building the scene's runtime (BVH, shadow maps and "
                  "volumes, tables) before rendering; reading the scene file excluded.\n"
                : " interleaved repeats (scene load and BVH build excluded).\n");
    out << "Reference: " << result.reference.description;
    if (result.reference.has_standard_error) {
        out << "; its own standard error (from the two halves): RMSE " +
                   g3(result.reference.standard_error.rmse) + ", relative MSE " +
                   g3(result.reference.standard_error.rel_mse);
    }
    out << ".\n\n";
    out << "Error against the reference: RMSE over pixels and channels ("
        << (result.probe.rfind("transmittance", 0) == 0 ? "transmittance" : "cd/m²")
        << "); relative MSE = mean of (a − b)² / (b² + ε) over pixels and channels with ε = ("
        << g3(e.eps_fraction) << " Ȳ)², Ȳ the reference's mean luminance; max ΔY/Y over pixels "
        << "whose reference luminance exceeds " << g3(e.floor_fraction)
        << " Ȳ; ΔȲ/Ȳ: relative error of the mean luminance (a bias shows there, noise averages "
           "out). Efficiency = 1 / (relative MSE × time): higher buys more accuracy per second. "
           "★ marks the Pareto front of (time, relative MSE); **bold**, the most efficient.\n\n";
    const bool spp_column = !has_spp_axis(result);
    out << "|";
    for (const StudyAxis& a : result.axes)
        out << " `" << a.key << "` |";
    if (spp_column)
        out << " spp |";
    out << " time, s | RMSE | rel. MSE | max ΔY/Y | ΔȲ/Ȳ | efficiency, 1/s | Pareto |\n|";
    for (size_t i = 0; i < result.axes.size() + (spp_column ? 1 : 0); ++i)
        out << "---|";
    out << "---:|---:|---:|---:|---:|---:|:---:|\n";
    const size_t best = best_efficiency(result);
    for (size_t i = 0; i < result.rows.size(); ++i) {
        const StudyRow& row = result.rows[i];
        const std::string b = i == best ? "**" : "";
        out << "|";
        for (const std::string& v : row.values)
            out << " " << b << shown(v) << b << " |";
        if (spp_column)
            out << " " << row.spp << " |";
        out << " " << g3(row.median_seconds) << " | " << g3(row.error.rmse) << " | "
            << g3(row.error.rel_mse) << " | " << g3(row.error.max_rel_luminance) << " | "
            << signed_percent(row.error.mean_luminance_error) << " | " << b << g3(row.efficiency)
            << b << " | " << (row.pareto ? "★" : "") << " |\n";
    }
    return out.str();
}

std::string study_svg(const StudyResult& result) {
    LinePlot plot;
    plot.title =
        "Study of " + std::filesystem::path(result.scene).filename().string() + " (" +
        (result.probe.empty() ? std::to_string(result.width) + "x" + std::to_string(result.height)
                              : result.probe) +
        ")";
    plot.x.label = result.timing == StudyTiming::BuildRender ? "build + render time, s (median)"
                                                             : "render time, s (median)";
    plot.y.label = "relative MSE against the reference";
    const std::string along = result.axes.empty() ? "" : result.axes.back().key;
    std::map<std::string, size_t> index;
    for (const StudyRow& row : result.rows) {
        std::string name;
        for (size_t a = 0; a + 1 < row.values.size(); ++a) {
            const std::string& v = row.values[a];
            name += (name.empty() ? "" : ", ") +
                    (v.empty() || v.front() != '{' ? short_key(result.axes[a].key) + "=" : "") +
                    shown(v);
        }
        if (name.empty())
            name = along.empty() ? "scene" : "along " + along;
        else if (!along.empty())
            name += " (along " + short_key(along) + ")";
        auto it = index.find(name);
        if (it == index.end()) {
            it = index.emplace(name, plot.series.size()).first;
            plot.series.push_back(PlotSeries{name, {}});
        }
        plot.series[it->second].points.push_back({row.median_seconds, row.error.rel_mse});
        if (row.pareto)
            plot.front.push_back({row.median_seconds, row.error.rel_mse});
    }
    return svg_line_plot(plot);
}

void write_study(const StudyResult& result, const std::string& dir) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec)
        throw_output_error(dir + ": cannot create directory: " + ec.message());
    const std::string files[3][2] = {{"study.csv", study_csv(result)},
                                     {"study.md", study_markdown(result)},
                                     {"study.svg", study_svg(result)}};
    for (const auto& f : files) {
        const std::string path = (std::filesystem::path(dir) / f[0]).string();
        write_file_atomic(path, f[1].data(), f[1].size());
    }
}

}  // namespace kasumi
