#pragma once
// What a catalogue run left in OUT, for people and for the next run
// (docs/batch.md): every item's state, the failures by class, summary.csv,
// summary.json and the contact sheet index.html.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "vgd/batch/catalogue.hpp"
#include "vgd/batch/item.hpp"

namespace vgd::batch {

struct Status {
  std::vector<ItemStatus> items;                 // per catalogue item, in index order
  int pending = 0, partial = 0, passed = 0, failed = 0;
  std::map<std::string, std::vector<int>> failed_by_class;  // class → indices
  std::vector<int> unfinished() const;           // pending and partial indices
  std::vector<int> failed_indices() const;
};

Status status(const Catalogue& catalogue, const std::filesystem::path& out, bool checksums = true);

// Writes OUT/summary.csv, OUT/summary.json and OUT/index.html (atomically),
// and, for the items with a garment.wrl, a 3-D viewer page each in OUT/web/
// (docs/vrml.md's web catalogue: X_ITE copied once into OUT/web/x_ite from
// `x_ite_dist`, by default the one this build found; no pages when there is
// none). Returns the number of viewer pages.
int write_summary(const Catalogue& catalogue, const std::filesystem::path& out, const Status& status,
                  const std::filesystem::path& x_ite_dist = {});

std::string summary_csv(const Catalogue& catalogue, const Status& status);
std::string summary_json(const Catalogue& catalogue, const Status& status);
// The contact sheet: a card per item (preview, style, size, fabric, avatar,
// pass/fail badge, the certificate's key figures, links to its outputs),
// filterable by style, size, fabric, avatar and state. Self-contained: no
// script or style from elsewhere.
// `viewer_pages`: link each item with a garment.wrl to web/<id>.html.
std::string contact_sheet_html(const Catalogue& catalogue, const Status& status, bool viewer_pages = false);

}  // namespace vgd::batch
