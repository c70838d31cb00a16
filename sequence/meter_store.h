#pragma once
/// Meterings of auto exposure kept on disk between processes (docs/sequences.md#auto-exposure):
/// a Slurm task rendering one frame needs the meterings of the 23 frames before it, which other
/// tasks have usually made already. A metering is a function of the frame's document, the meter
/// render's size and the kasumi build alone (sequence/auto_exposure.h), so a stored value is
/// exactly the value a new meter render would give, and reading it changes no exposure.
///
/// One small JSON file per metering, named by a hash of what it depends on, in a directory
/// beside the frames (out/.kasumi-meter/), written atomically: tasks on different nodes never
/// see half a file and never need a lock. A file that cannot be read, does not parse or was
/// made for another document (the hash is 64-bit FNV-1a, so the document's length is checked
/// too) is a miss: the frame is metered again and the file replaced.
#include <optional>
#include <string>

namespace kasumi {

class MeterStore {
  public:
    /// `dir` empty: a store that never finds anything and writes nothing.
    explicit MeterStore(std::string dir);

    /// The stored log2 luminance of the document whose JSON text is `document`, if any.
    std::optional<double> find(const std::string& document) const;

    /// Stores `log2_luminance` for `document`; creates the directory. A store that cannot be
    /// written is not an error of the sequence (the frame's exposure is already known): the
    /// reason is returned (empty on success) for the caller to report once.
    std::string put(const std::string& document, double log2_luminance) const;

    const std::string& dir() const { return m_dir; }

  private:
    std::string file_of(const std::string& document) const;
    std::string m_dir;
};

/// The store beside the frames of `output_pattern` (its directory's .kasumi-meter).
std::string meter_store_dir(const std::string& output_pattern);

}  // namespace kasumi
