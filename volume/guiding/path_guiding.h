#pragma once
/// What one volume path needs to be guided and to train the guide, and the bookkeeping that
/// turns a path into training records.
#include "core/color.h"
#include "volume/guiding/guiding_field.h"

#include <array>
#include <vector>

namespace kasumi {

/// The guide a path samples from (null: phase sampling only) and where its training records go
/// (null: none).
struct PathGuiding {
    const GuidingField* field = nullptr;
    float mix = 0.5f;  ///< GuidingSettings::mix
    std::vector<GuidingRecord>* records = nullptr;
};

/// The scattering vertices of one path, each with the throughput just after its direction was
/// sampled (f / pdf applied, Russian roulette not yet). Radiance the path gathers later, added
/// as throughput x L, reaches every earlier vertex as (throughput x L) / throughput_vertex:
/// the incident radiance along that vertex's direction (Müller et al. 2017, sec. 5.2; the same
/// for volume vertices, Herholz et al. 2019 sec. 6).
class GuidingPathRecorder {
  public:
    static constexpr int kMaxVertices = 32;  ///< deeper vertices are not recorded

    explicit GuidingPathRecorder(const PathGuiding* guiding)
        : m_records(guiding != nullptr ? guiding->records : nullptr) {}
    GuidingPathRecorder(const GuidingPathRecorder&) = delete;
    GuidingPathRecorder& operator=(const GuidingPathRecorder&) = delete;
    ~GuidingPathRecorder() { finish(); }

    bool active() const { return m_records != nullptr; }
    /// A vertex at `position` continued in `wi` (drawn with density pdf_sr), `throughput` after it.
    void vertex(const Vec3& position, const Vec3& wi, float pdf_sr, const Rgb& throughput) {
        if (m_records != nullptr)
            record_vertex(position, wi, pdf_sr, throughput);
    }
    /// Radiance the path gathered (already multiplied by the path's throughput), cd/m².
    void add(const Rgb& contribution) {
        if (m_records != nullptr)
            record_radiance(contribution);
    }
    /// Appends the records of the path's vertices (once; the destructor calls it).
    void finish() {
        if (m_records != nullptr)
            flush();
    }

  private:
    // The recording itself, out of line: a path that records nothing (rendering without
    // training) pays one test per call.
    void record_vertex(const Vec3& position, const Vec3& wi, float pdf_sr, const Rgb& throughput);
    void record_radiance(const Rgb& contribution);
    void flush();

    /// Left uninitialised until recorded (record_vertex writes every member): the recorder
    /// lives on the stack of every path, most of which record nothing.
    struct Vertex {
        Vec3 position;
        Vec3 wi;
        float pdf;
        Rgb throughput;
        Rgb incident;
    };
    std::vector<GuidingRecord>* m_records;
    std::array<Vertex, kMaxVertices> m_vertices;
    int m_count = 0;
};

}  // namespace kasumi
