// The report page's own files (src/app/report/: the page, its script and style), built into
// the program so that `vdcloth report` needs nothing beside it but Debian's libraries.
#pragma once
#include <span>
#include <string_view>

namespace vdc {

struct ReportAsset {
  std::string_view name;  // the file's name in the report folder
  std::string_view text;
};

// Generated at build time from src/app/report/ (cmake/embed_report_assets.cmake).
std::span<const ReportAsset> report_assets();

}  // namespace vdc
