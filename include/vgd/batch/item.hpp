#pragma once
// One work item (docs/batch.md): drape → certificate → outputs → previews,
// as the vgd commands a designer would type (dress, compress, export), each
// run as a child process with its output in the item's log.txt. The item is
// made in OUT/items/<id>.partial/ and renamed to OUT/items/<id>/ when its
// manifest.json is written, so an item folder is either whole or absent.
//
// An item is finished when its manifest verifies (every file listed is there
// with its size and SHA-256): passed (the certificate passed) or failed,
// with a failure class. A rerun skips finished items and redoes the rest.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "vgd/batch/catalogue.hpp"

namespace vgd::batch {

// Failure classes, a fixed list (after GarmentCodeData's): an input vgd
// refused ("bad input"), the engine stopping ("diverged"), an allocation
// past the item's memory ("out of memory"), the process
// killed by a signal ("crash"), the item's wall limit ("time-out"), an
// output step failing ("output"), or the certificate's first failed check
// ("no rest", "seams open", "open side", "body penetration",
// "self-intersection", "over-stretched", "displaced").
std::string failure_class_of_check(const std::string& certificate_kind);

struct Step {
  std::string name;               // dress, compress, export, export-animated
  std::vector<std::string> args;  // after the vgd executable
};

// The commands item `item` runs, writing into `dir`.
std::vector<Step> item_steps(const Catalogue& catalogue, const Item& item, const std::filesystem::path& dir);

struct FileEntry {
  std::string path;  // relative to the item's folder, '/'-separated
  std::uintmax_t bytes = 0;
  std::string sha256;
};

struct StepRecord {
  std::string name;    // dress, compress, export, export-animated
  double wall_s = 0.0;
  std::string result;  // "exit 0", "killed by signal 11 (...)", ...
};

struct Manifest {
  std::string id, name, style, size, fabric, avatar;
  int index = 0;
  std::string state;            // "passed" or "failed"
  std::string failure_class;    // "" when passed
  std::string failure_message;
  double wall_s = 0.0;
  std::string started, finished;  // UTC, ISO 8601
  std::string vgd_version;
  std::string certificate;      // key figures of certificate.json, as JSON text ("" when none)
  std::vector<StepRecord> steps;  // where the time went
  std::vector<FileEntry> files;
};

std::string to_json(const Manifest& m);
Manifest manifest_from_json(const std::string& text, const std::string& file);

enum class ItemState { pending, partial, passed, failed };
const char* to_string(ItemState s);

struct ItemStatus {
  ItemState state = ItemState::pending;
  std::optional<Manifest> manifest;  // when finished
  std::string problem;               // why a folder there does not count (partial)
};

// Where item `id`'s results are under OUT.
std::filesystem::path item_dir(const std::filesystem::path& out, const std::string& id);

// The item's state: its manifest read and verified (sizes always; SHA-256
// too when `checksums`).
ItemStatus item_status(const std::filesystem::path& out, const Item& item, bool checksums = true);

struct RunItemOptions {
  std::filesystem::path exe;   // the vgd executable the steps run
  bool retry_failed = false;   // redo an item that finished failed
  bool force = false;          // redo it whatever its state
};

struct ItemOutcome {
  bool skipped = false;  // already finished
  Manifest manifest;
};

// Runs item `item` into OUT/items/<id>/ (see above). Never throws for what
// the item's steps do (that is the item's failure); throws vgd::Error when
// OUT cannot be written.
ItemOutcome run_item(const Catalogue& catalogue, const Item& item, const std::filesystem::path& out,
                     const RunItemOptions& options);

// Records a finished, failed item without outputs (a worker killed before it
// wrote its manifest): OUT/items/<id>/manifest.json with `failure_class`.
void record_failure(const std::filesystem::path& out, const Catalogue& catalogue, const Item& item,
                    const std::string& failure_class, const std::string& message);

}  // namespace vgd::batch
