#pragma once
// Continuing a run: which configuration changes a restart may not make, and how the time
// series and the field index are brought back to the checkpoint's step.
#include <string>
#include <utility>
#include <vector>

#include "config/case_config.hpp"
#include "io/field_writer.hpp"

namespace eulerfsi {

// Keys of [domain], [flow] and [[solid]] whose values differ between two resolved configurations
// (time stepping and output may change on restart; the physics may not).
std::vector<std::string> differing_physical_keys(const CaseConfig& before, const CaseConfig& now);

// Drops the rows of a CSV time series whose first column (step) is beyond `step`, atomically.
// A missing file is created with just `header` later by the writer: nothing to do here. When
// `columns` is given and the file was written with others (an older or newer eulerfsi), the kept
// rows are rewritten under `columns` by name ("nan" where a column is new), the original kept as
// CSV_PATH.before-restart, and true returned: the rows the restart appends then match the header.
bool truncate_series_after(const std::string& csv_path, long step, const std::vector<std::string>& columns = {});

// (step, t, frame offset) of the field snapshots fields/NNNNNNNN.h5 at or before `step`, oldest first.
std::vector<Snapshot> field_history_until(const std::string& run_dir, long step);

}  // namespace eulerfsi
