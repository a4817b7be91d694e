#pragma once
// Helpers shared by the Store's source files: pose columns, binding and reading poses.
#include <string>

#include "strata/store/sqlite_db.h"
#include "strata/store/store_codec.h"

namespace strata::store::detail {

/// "P_tx, P_ty, P_tz, P_qx, P_qy, P_qz, P_qw".
std::string poseColumns(const std::string& prefix);
/// "?, ?, ..." with `n` placeholders.
std::string placeholders(int n);
/// Binds the 7 values of T at first_index .. first_index + 6 (NULLs for nullopt).
void bindPose(Statement& s, int first_index, const std::optional<Eigen::Isometry3d>& T);
/// Reads 7 columns from first_column; nullopt when they are NULL.
std::optional<Eigen::Isometry3d> readPose(const Statement& s, int first_column,
                                          const std::string& what);

}  // namespace strata::store::detail
