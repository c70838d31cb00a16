#pragma once
/// Writes a study's results: DIR/study.csv (one row per configuration), DIR/study.md (a table
/// with the method stated) and DIR/study.svg (relative MSE against time, log-log).
#include "study/study.h"

#include <string>

namespace kasumi {

std::string study_csv(const StudyResult& result);
std::string study_markdown(const StudyResult& result);
/// One line per combination of all axes but the last; the last axis runs along each line.
std::string study_svg(const StudyResult& result);

/// Creates `dir` and writes the three files, each atomically; ErrorKind::Output on failure.
void write_study(const StudyResult& result, const std::string& dir);

}  // namespace kasumi
