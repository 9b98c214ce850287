#include "vgd/pattern/roles.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <initializer_list>
#include <set>

#include "vgd/core/strings.hpp"

namespace vgd::pattern {

namespace {

// ---- folding --------------------------------------------------------------------------

// Latin-1 letters with accents -> their ASCII base letter(s), upper case; 0 = not a letter.
const char* latin1_base(std::uint32_t c) {
  static constexpr std::array<const char*, 64> table = {
      "A", "A", "A", "A", "A", "A", "AE", "C",     "E", "E", "E", "E", "I", "I", "I",  "I",   // C0-CF
      "D", "N", "O", "O", "O", "O", "O",  nullptr, "O", "U", "U", "U", "U", "Y", "TH", "SS",  // D0-DF
      "A", "A", "A", "A", "A", "A", "AE", "C",     "E", "E", "E", "E", "I", "I", "I",  "I",   // E0-EF
      "D", "N", "O", "O", "O", "O", "O",  nullptr, "O", "U", "U", "U", "U", "Y", "TH", "Y",   // F0-FF
  };
  return c >= 0xC0 && c <= 0xFF ? table[c - 0xC0] : nullptr;
}

bool is_letter(std::uint32_t c) {
  if (c < 0x80) return std::isalnum(static_cast<int>(c)) != 0;
  if (c >= 0xC0 && c <= 0xFF) return latin1_base(c) != nullptr;
  if (c >= 0x80 && c < 0xC0) return false;      // Latin-1 punctuation and signs
  if (c >= 0x2000 && c < 0x2070) return false;  // general punctuation
  return c != vgd::kInvalidUtf8;
}

// ---- words ----------------------------------------------------------------------------

struct Token {
  std::string text;        // folded
  bool used = false;       // decided a role, a side or is a modifier
  bool described = false;  // follows WITH, NO, ...: matches no dictionary word
};

std::size_t letters(std::string_view w) {
  std::size_t n = 0;
  for (const char ch : w) n += (static_cast<unsigned char>(ch) & 0xC0) != 0x80;
  return n;
}

std::vector<Token> tokens_of(const std::string& folded) {
  std::vector<Token> out;
  std::string cur;
  std::size_t i = 0;
  while (i < folded.size()) {
    const std::size_t start = i;
    const std::uint32_t c = vgd::next_utf8(folded, i);
    if (is_letter(c)) {
      cur.append(folded, start, i - start);
    } else if (!cur.empty()) {
      out.push_back({cur});
      cur.clear();
    }
  }
  if (!cur.empty()) out.push_back({cur});
  return out;
}

bool only_digits(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
}

// How a dictionary entry matches a token:
//   "WORD"   the token is WORD, or WORD and digits; a word of 4 or more letters also
//            matches inside a run-together token (FRONTPANEL)
//   "=WORD"  whole token only (with digits)
//   "*WORD"  a token starting with WORD (inflections: DELANTER*, ЛЕВ*)
//   "$CODE"  as "=CODE", or at the end of a longer token, digits allowed after it
//            (Gerber's style code + piece code: TEEBK1, TEESL)
struct Hit {
  bool found = false;
  std::size_t token = 0;
  std::size_t pos = 0, len = 0;  // where in the token
};

Hit match(const std::vector<Token>& toks, std::string_view entry) {
  char mode = ' ';
  if (entry[0] == '=' || entry[0] == '*' || entry[0] == '$') {
    mode = entry[0];
    entry.remove_prefix(1);
  }
  const bool inside = mode == ' ' && letters(entry) >= 4;
  for (std::size_t t = 0; t < toks.size(); ++t) {
    const std::string& s = toks[t].text;
    if (toks[t].described) continue;
    if (s.rfind(entry, 0) == 0) {
      const std::string_view rest = std::string_view(s).substr(entry.size());
      if (rest.empty() || only_digits(rest) || mode == '*') return {true, t, 0, s.size()};
    }
    if (mode == '$' && s.size() > entry.size()) {
      std::size_t end = s.size();
      while (end > 0 && s[end - 1] >= '0' && s[end - 1] <= '9') --end;
      if (end > entry.size() && s.compare(end - entry.size(), entry.size(), entry) == 0)
        return {true, t, end - entry.size(), entry.size()};
    }
    if (inside) {
      const std::size_t at = s.find(entry);
      if (at != std::string::npos) return {true, t, at, entry.size()};
    }
  }
  return {};
}

struct Concept {
  std::initializer_list<const char*> words;
};

// The dictionary: English, Spanish, Portuguese, German, French, Russian; Gerber codes.
// Upper case, accents folded (fold_name).
const Concept kLabel{{"LABEL", "ETIQUETA", "ETIKETT", "ETIQUETTE", "ЭТИКЕТКА", "=LBL"}};
const Concept kInterfacing{{"INTERFACING", "INTERFACE", "INTERLINING", "INTERLIN", "FUSIBLE", "FUSING",
                            "ENTRETELA", "ENTRETELA", "EINLAGE", "ENTOILAGE", "THERMOCOLLANT", "ДУБЛЕРИН",
                            "ФЛИЗЕЛИН", "=INTF", "=FUS"}};
const Concept kLining{{"LINING", "FORRO", "FUTTER", "DOUBLURE", "ПОДКЛАДКА", "=LNG", "=LINE"}};
const Concept kFlap{{"FLAP", "KLAPPE", "TASCHENPATTE", "RABAT", "КЛАПАН", "=FLP"}};
const Concept kFlapWord{{"=TAPA", "=PATTE", "=PORTINHOLA"}};
const Concept kPocket{
    {"POCKET", "BOLSILLO", "=BOLSO", "TASCHE", "POCHE", "КАРМАН", "*КАРМАН", "$PKT", "=PCKT", "=POC"}};
const Concept kLoop{
    {"BELTLOOP", "TRABILLA", "PASADOR", "PASSANTE", "PASSANT", "SCHLAUFE", "ШЛЕВКА", "*ШЛЁВК", "=LOOP"}};
const Concept kFly{
    {"=FLY", "FLYSHIELD", "BRAGUETA", "BRAGUILHA", "HOSENSCHLITZ", "BRAGUETTE", "ГУЛЬФИК", "=ZIPPER"}};
const Concept kCuff{
    {"CUFF", "$CUF", "=PUNO", "PUNHO", "MANSCHETTE", "BUNDCHEN", "POIGNET", "МАНЖЕТ", "*МАНЖЕТ"}};
const Concept kNeckband{{"NECKBAND", "NECKRIB", "RIBCOLLAR", "COLLARRIB", "HALSBUND"}};
const Concept kNeck{{"NECK", "CUELLO", "HALS", "ГОРЛОВИН"}};
const Concept kRib{{"=RIB", "=RIBANA", "RIPP", "=RIPPE"}};
const Concept kBand{{"=BAND", "=BANDE", "=BANDA"}};
const Concept kStand{{"STAND", "=BASE", "BASE", "STEG", "=PIE", "=PIED", "=PE", "СТОЙКА", "*СТОЙК"}};
const Concept kCollar{
    {"COLLAR", "$CLR", "=CO", "=COL", "CUELLO", "=GOLA", "COLARINHO", "KRAGEN", "ВОРОТНИК", "*ВОРОТНИК"}};
const Concept kPlacket{
    {"PLACKET", "=PLKT", "=PLK", "TAPETA", "CARCELA", "KNOPFLEISTE", "LEISTE", "ПЛАНКА", "*ПЛАНК"}};
const Concept kFacing{{"FACING", "=FCG", "VISTA", "BELEG", "PAREMENT", "ПОДБОРТ", "*ПОДБОРТ"}};
const Concept kBinding{{"BINDING", "=BIAS", "=VIVO", "=VIES", "SCHRAGBAND", "EINFASS", "=BIAIS", "ОКАНТОВК",
                        "*ОКАНТОВК", "=БЕЙКА"}};
const Concept kYoke{{"YOKE", "$YK", "CANESU", "=PALA", "=PASSE", "EMPIECEMENT", "КОКЕТКА", "*КОКЕТК"}};
const Concept kHood{{"=HOOD", "CAPUCHA", "CAPUZ", "KAPUZE", "CAPUCHE", "КАПЮШОН"}};
const Concept kWaistband{{"WAISTBAND", "$WB", "=WSTBD", "=WSTB", "PRETINA", "=COS", "=BUND", "BUNDBAND",
                          "CEINTURE", "=ПОЯС", "*ПОЯС"}};
const Concept kWaist{{"WAIST", "CINTURA", "TAILLE"}};
const Concept kSleeve{{"SLEEVE", "$SLV", "$SL", "=MANGA", "ARMEL", "AERMEL", "MANCHE", "РУКАВ", "*РУКАВ"}};
const Concept kLeg{{"=LEG", "=LEGS", "=TIGHT", "=TIGHTS", "PIERNA", "=PERNA", "HOSENBEIN", "=BEIN", "JAMBE",
                    "ШТАНИН", "*ШТАНИН"}};
// Trousers, pants: with a front or back word the piece is half of a leg.
const Concept kTrouser{{"TROUSER", "TROUSERS", "=PANT", "=PANTS", "PANTALON", "PANTALONES", "=CALCA", "HOSE", "БРЮКИ",
                        "*БРЮК"}};
const Concept kFront{{"FRONT", "$FR", "$FRT", "=FT", "DELANTER", "*DELANTER", "FRENTE", "VORDERTEIL",
                      "VORDERHOSE", "*VORDER", "DEVANT", "=ПЕРЕД", "*ПЕРЕД", "ПОЛОЧКА", "*ПОЛОЧК"}};
const Concept kBack{{"BACK", "$BK", "$BCK", "ESPALDA", "TRASER", "*TRASER", "COSTAS", "RUCKEN", "RUECKEN",
                     "HINTERTEIL", "HINTERHOSE", "*HINTER", "=DOS", "СПИНКА", "*СПИНК", "*ЗАДН"}};
const Concept kLeft{{"LEFT", "=LT", "=LFT", "*IZQUIERD", "*ESQUERD", "=LINKS", "*LINKE", "GAUCHE", "*ЛЕВ"}};
const Concept kRight{{"RIGHT", "=RT", "=RGT", "*DERECH", "*DIREIT", "=RECHTS", "*RECHTE", "*DROIT", "*ПРАВ"}};
// Words that make the next one a description, not a name (FRONT WITH POCKET).
const Concept kModifier{{"=WITH", "=W", "=WITHOUT", "=NO", "=CON", "=SIN", "=COM", "=SEM", "=MIT", "=OHNE",
                         "=AVEC", "=SANS", "=С", "=БЕЗ"}};
// What a piece is cut from: the annotation's fabric words.
const Concept kFabric{{"FABRIC", "SELF", "SHELL", "=RIB", "TELA", "TECIDO", "STOFF", "TISSU", "ТКАНЬ"}};

using Found = std::vector<Hit>;  // where a concept's words matched

Found find(const std::vector<Token>& toks, const Concept& c) {
  Found f;
  for (const char* w : c.words)
    if (const Hit h = match(toks, w); h.found) f.push_back(h);
  return f;
}

}  // namespace

std::string fold_name(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t start = i;
    const std::uint32_t c = vgd::next_utf8(text, i);
    if (c == vgd::kInvalidUtf8) {
      out.append(text.substr(start, i - start));
    } else if (c < 0x80) {
      out += static_cast<char>(c >= 'a' && c <= 'z' ? c - 'a' + 'A' : c);
    } else if (const char* base = latin1_base(c)) {
      out += base;
    } else if (c >= 0x0430 && c <= 0x044F) {  // Cyrillic а..я
      vgd::append_utf8(out, c - 0x20);
    } else if (c >= 0x0450 && c <= 0x045F) {  // ѐ..џ (ё among them)
      vgd::append_utf8(out, c == 0x0451 ? 0x0415 : c - 0x50);
    } else if (c == 0x0401) {  // Ё reads as Е
      vgd::append_utf8(out, 0x0415);
    } else {
      vgd::append_utf8(out, c);
    }
  }
  return out;
}

std::string_view role_name(Role role) {
  switch (role) {
    case Role::unknown:
      return "unknown";
    case Role::front:
      return "front";
    case Role::back:
      return "back";
    case Role::sleeve:
      return "sleeve";
    case Role::leg:
      return "leg";
    case Role::collar:
      return "collar";
    case Role::collar_stand:
      return "collar stand";
    case Role::neckband:
      return "neckband";
    case Role::hood:
      return "hood";
    case Role::yoke:
      return "yoke";
    case Role::cuff:
      return "cuff";
    case Role::waistband:
      return "waistband";
    case Role::placket:
      return "placket";
    case Role::facing:
      return "facing";
    case Role::binding:
      return "binding";
    case Role::pocket:
      return "pocket";
    case Role::pocket_flap:
      return "pocket flap";
    case Role::belt_loop:
      return "belt loop";
    case Role::fly:
      return "fly";
    case Role::lining:
      return "lining";
    case Role::interfacing:
      return "interfacing";
    case Role::label:
      return "label";
  }
  return "unknown";
}

const std::vector<Role>& all_roles() {
  static const std::vector<Role> roles = [] {
    std::vector<Role> v;
    for (int r = static_cast<int>(Role::unknown); r <= static_cast<int>(Role::label); ++r) v.push_back(static_cast<Role>(r));
    return v;
  }();
  return roles;
}

std::optional<Role> role_from_name(std::string_view name) {
  std::string spaced(name);
  std::replace(spaced.begin(), spaced.end(), '_', ' ');
  for (const Role r : all_roles())
    if (role_name(r) == spaced) return r;
  return std::nullopt;
}

std::string_view side_name(Side side) {
  return side == Side::left ? "left" : side == Side::right ? "right" : "";
}

std::string_view half_name(Half half) {
  return half == Half::front ? "front half" : half == Half::back ? "back half" : "";
}

bool drapes_as_cloth(Role role) {
  return role != Role::interfacing && role != Role::label && role != Role::lining;
}

bool sewn_on_host(Role role) {
  return role == Role::pocket || role == Role::pocket_flap || role == Role::belt_loop ||
         role == Role::placket || role == Role::facing || role == Role::fly;
}

RoleGuess piece_role(std::string_view name, std::string_view category, std::string_view annotation,
                     std::string_view style) {
  std::string n = fold_name(name);
  const std::string st = fold_name(style);
  // A Gerber name that starts with the style's name: the rest names the piece.
  if (!st.empty() && n.size() > st.size() && n.rfind(st, 0) == 0) n = n.substr(st.size());
  std::vector<Token> toks = tokens_of(n + " " + fold_name(category));
  // WITH POCKET, NO POCKET: the described word does not name the piece.
  for (std::size_t t = 0; t + 1 < toks.size(); ++t) {
    std::vector<Token> one{toks[t]};
    if (!find(one, kModifier).empty()) {
      toks[t].used = true;
      toks[t + 1].used = true;
      toks[t + 1].described = true;
    }
  }
  RoleGuess g;
  const auto use = [&](const Found& f) {
    for (const Hit& h : f) toks[h.token].used = true;
  };
  const auto take = [&](Role r, const Found& f) {
    g.role = r;
    use(f);
    const Hit& h = f.front();
    g.word = toks[h.token].text.substr(h.pos, h.len);
  };
  const Found label = find(toks, kLabel), interfacing = find(toks, kInterfacing),
              lining = find(toks, kLining), flap = find(toks, kFlap), flap_word = find(toks, kFlapWord),
              pocket = find(toks, kPocket), loop = find(toks, kLoop), fly = find(toks, kFly),
              cuff = find(toks, kCuff), neckband = find(toks, kNeckband), neck = find(toks, kNeck),
              rib = find(toks, kRib), stand = find(toks, kStand), band = find(toks, kBand),
              collar = find(toks, kCollar), placket = find(toks, kPlacket), facing = find(toks, kFacing),
              binding = find(toks, kBinding), yoke = find(toks, kYoke), hood = find(toks, kHood),
              waistband = find(toks, kWaistband), waist = find(toks, kWaist), sleeve = find(toks, kSleeve),
              leg = find(toks, kLeg), trouser = find(toks, kTrouser), front = find(toks, kFront), back = find(toks, kBack);
  // The annotation says what the piece is cut from: interlining alone makes an interfacing.
  std::vector<Token> ann = tokens_of(fold_name(annotation));
  const bool cut_from_interlining = !find(ann, kInterfacing).empty() && find(ann, kFabric).empty();

  if (!label.empty())
    take(Role::label, label);
  else if (!interfacing.empty())
    take(Role::interfacing, interfacing);
  else if (cut_from_interlining)
    g.role = Role::interfacing, g.word = fold_name(annotation);
  else if (!lining.empty())
    take(Role::lining, lining);
  else if (!flap.empty())
    take(Role::pocket_flap, flap);
  else if (!pocket.empty() && !flap_word.empty())
    take(Role::pocket_flap, flap_word), use(pocket);
  else if (!pocket.empty())
    take(Role::pocket, pocket);
  else if (!loop.empty())
    take(Role::belt_loop, loop);
  else if (!fly.empty())
    take(Role::fly, fly);
  else if (!cuff.empty())
    take(Role::cuff, cuff);
  else if (!neckband.empty())
    take(Role::neckband, neckband);
  else if (!neck.empty() && (!rib.empty() || !band.empty()))
    take(Role::neckband, neck), use(rib), use(band);
  else if (!collar.empty() && !rib.empty())
    take(Role::neckband, collar), use(rib);
  else if (!collar.empty() && (!stand.empty() || !band.empty()))
    take(Role::collar_stand, collar), use(stand), use(band);
  else if (!collar.empty())
    take(Role::collar, collar);
  else if (!placket.empty())
    take(Role::placket, placket);
  else if (!facing.empty())
    take(Role::facing, facing);
  else if (!binding.empty())
    take(Role::binding, binding);
  else if (!yoke.empty())
    take(Role::yoke, yoke);
  else if (!hood.empty())
    take(Role::hood, hood);
  else if (!waistband.empty())
    take(Role::waistband, waistband);
  else if (!waist.empty() && (!rib.empty() || !band.empty()))
    take(Role::waistband, waist), use(rib), use(band);
  else if (!sleeve.empty())
    take(Role::sleeve, sleeve);
  else if (!leg.empty())
    take(Role::leg, leg);
  else if (!trouser.empty())
    take(Role::leg, trouser);
  else if (!front.empty())
    take(Role::front, front);
  else if (!back.empty())
    take(Role::back, back);

  // A sleeve's or leg's front or back word makes it a half of a sleeve cut in
  // two or of a trouser leg; the name's word over the category's (Gerber files
  // swap the two halves' categories).
  if (g.role == Role::sleeve || g.role == Role::leg) {
    const std::size_t name_tokens = tokens_of(n).size();
    const auto in = [&](const Found& f, bool name_part) {
      return std::any_of(f.begin(), f.end(), [&](const Hit& h) { return (h.token < name_tokens) == name_part; });
    };
    bool fr = in(front, true), bk = in(back, true);
    if (!fr && !bk) fr = in(front, false), bk = in(back, false);
    if (fr != bk) {
      g.half = fr ? Half::front : Half::back;
      for (const Hit& h : fr ? front : back) toks[h.token].used = true;
    }
  }
  const Found left = find(toks, kLeft), right = find(toks, kRight);
  if (!left.empty() != !right.empty()) {
    g.side = !left.empty() ? Side::left : Side::right;
    use(!left.empty() ? left : right);
  }
  // The rest of the name tells alternatives apart (SHORT, LONG, HALF, FULL, ...); what is
  // left of a run-together token counts too (SHORTSLEEVE -> SHORT).
  std::set<std::string> seen;
  for (std::size_t t = 0; t < toks.size(); ++t) {
    std::string w = toks[t].text;
    if (toks[t].used) {
      if (g.word.empty() || w.find(g.word) == std::string::npos || w == g.word) continue;
      const std::size_t at = w.find(g.word);
      const std::string before = w.substr(0, at), after = w.substr(at + g.word.size());
      w = before.size() >= after.size() ? before : after;
      if (letters(w) < 2 || only_digits(w)) continue;
    }
    if (w.empty() || toks[t].described || only_digits(w)) continue;
    if (seen.insert(w).second) g.variant.push_back(w);
  }
  return g;
}

}  // namespace vgd::pattern
