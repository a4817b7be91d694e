#include "strata/store/internal/store_sql.h"

namespace strata::store::detail {

std::string poseColumns(const std::string& prefix) {
  std::string out;
  for (const char* c : {"tx", "ty", "tz", "qx", "qy", "qz", "qw"}) {
    out += (out.empty() ? "" : ", ") + prefix + "_" + c;
  }
  return out;
}

std::string placeholders(int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += i == 0 ? "?" : ", ?";
  return out;
}

void bindPose(Statement& s, int first_index, const std::optional<Eigen::Isometry3d>& T) {
  if (!T) {
    for (int i = 0; i < 7; ++i) s.bindNull(first_index + i);
    return;
  }
  const auto values = poseToValues(*T);
  for (int i = 0; i < 7; ++i) s.bind(first_index + i, values[static_cast<std::size_t>(i)]);
}

std::optional<Eigen::Isometry3d> readPose(const Statement& s, int first_column,
                                          const std::string& what) {
  if (s.isNull(first_column)) return std::nullopt;
  std::array<double, 7> values{};
  for (int i = 0; i < 7; ++i) values[static_cast<std::size_t>(i)] = s.getDouble(first_column + i);
  return poseFromValues(values, what);
}

}  // namespace strata::store::detail
