#pragma once
// Catalogue runs (docs/batch.md): a catalogue.json names styles, sizes,
// fabrics and bodies; it expands to work items, one per style × size ×
// fabric × avatar, in a fixed order (style, then size, fabric, avatar), so
// item I is the same item on every machine that reads the same catalogue.
//
// Each item has a stable id: the SHA-256 of every input file's content and
// every setting that changes its result (catalogue paths and the catalogue's
// other items do not), so editing one style's file re-runs only that style's
// items. The index is where a scheduler's array task finds its item; the id
// is where its results live (OUT/items/<id>/).
#include <filesystem>
#include <string>
#include <vector>

namespace vgd::batch {

struct Style {
  std::string id;                 // the catalogue's name for it (unique)
  std::filesystem::path file;     // DXF or XVC (a document vgd dress wrote and a designer corrected)
  std::vector<std::string> sizes; // its own sizes, else the catalogue's ("sample" = the sample size)
  std::filesystem::path seams;    // a seam file sewing it instead of vgd's suggestions (vgd dress --seams); optional
  std::string sha256;             // of the file's content (and the seam file's)
};

// A fabric: the garment's own MATERIAL ("garment"), a shipped one
// (data/materials/<id>.xvc) or a MATERIAL in a document of the catalogue's.
struct Fabric {
  std::string id;
  std::filesystem::path file;  // empty: the garment's own
  std::string material;        // MATERIAL id in file; empty: its first
  std::string sha256;
};

// A body: the mannequin of the item's size ("mannequin"), a mannequin of a
// fixed size and table, a mannequin of a measurement set (a customer's
// measurements: `vgd mannequin --height ... --bust ...`), or a body file
// (OBJ, glTF, FBX, ...).
struct Avatar {
  enum class Kind { garment_size, mannequin, file, measurements };
  std::string id;
  Kind kind = Kind::garment_size;
  std::string size, table;                        // mannequin
  std::string sex;                                // measurements: female or male ("" = the mannequin's default)
  std::vector<std::pair<std::string, double>> measurements;  // vgd mannequin's option names (height, bust, ...), m
  std::filesystem::path file;                     // file
  std::string unit = "auto", up = "auto", facing = "auto";
  std::string sha256;
};

struct Settings {
  std::string quality = "standard";   // preview, standard, precise (vgd drape --quality)
  std::string model = "mass-spring";  // cloth model
  double time_limit = 8.0;            // s simulated, per drape
  double spacing = 0.0;               // m; 0 = the document's
  double wall_limit = 1800.0;         // s of wall time per item (all its steps), then "time-out"
  int memory_mb = 4096;               // per item: its processes' address space (RLIMIT_AS), and Slurm's --mem
  int threads = 1;                    // OpenMP threads per item
};

// What an item writes beside its certificate.json, garment.xvc, garment.obj
// and avatar.obj (always written).
struct Outputs {
  bool trj = false;            // drape.trj, every frame
  bool wvt = false;            // drape.wvt, compressed
  bool vrml = false;           // garment.wrl (static)
  bool vrml_animated = false;  // garment-animated.wrl.gz
  bool glb = false;            // garment.glb
  bool previews = true;        // previews/<view>.png
  std::vector<std::string> views = {"front", "three-quarter"};
  int preview_size = 512;      // px
};

struct Item {
  int index = 0;
  std::string id;    // 16 hex digits of the SHA-256 of its inputs
  std::string name;  // "<style> <size> <fabric> <avatar>", for people
  int style = 0, fabric = 0, avatar = 0;  // into the catalogue's lists
  std::string size;
};

struct Catalogue {
  std::filesystem::path file;  // the catalogue.json read (absolute)
  std::string name;
  std::vector<Style> styles;
  std::vector<Fabric> fabrics;
  std::vector<Avatar> avatars;
  Settings settings;
  Outputs outputs;
  std::vector<Item> items;
};

// Reads and validates a catalogue, hashes its files and expands its items.
// Paths are relative to the catalogue's folder. Throws vgd::Error naming the
// catalogue, the field ("styles[1].file") and the problem: unknown keys,
// missing files, duplicate ids, a value out of range.
Catalogue load_catalogue(const std::filesystem::path& file);

// The item `index`; throws vgd::Error naming the catalogue when there is none.
const Item& item_at(const Catalogue& catalogue, int index);

// The SHA-256 of a file's content (hex); throws vgd::Error when unreadable.
std::string sha256_file(const std::filesystem::path& file);
std::string sha256_hex(std::string_view bytes);

}  // namespace vgd::batch
