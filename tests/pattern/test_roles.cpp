// Piece roles from the names real CAD files write (pattern/roles.hpp).
#include <gtest/gtest.h>

#include "vgd/pattern/roles.hpp"

using namespace vgd::pattern;

namespace {

struct Case {
  const char* name;
  const char* category;
  const char* annotation;
  const char* style;
  Role role;
  Side side;
};

void expect(const Case& c) {
  const RoleGuess g = piece_role(c.name, c.category, c.annotation, c.style);
  EXPECT_EQ(role_name(g.role), role_name(c.role))
      << c.name << " / " << c.category << " (word '" << g.word << "')";
  EXPECT_EQ(side_name(g.side), side_name(c.side)) << c.name << " / " << c.category;
}

}  // namespace

// Names and categories as Gerber AccuMark, Valentina and CLO write them in the
// shared files: code names whose category says what the piece is, run-together
// names, style codes in front of the piece's own code.
TEST(PieceRole, NamesFromRealCadFiles) {
  const Case cases[] = {
      {"REGULAR TEEBK1", "", "1XFABRIC", "MEN CLASSIC TEE", Role::back, Side::none},
      {"REGULAR TEESL FR", "", "2XFABRIC", "MEN CLASSIC TEE", Role::sleeve, Side::none},
      {"TEE FR", "FRONT", "1XFABRIC", "MEN CLASSIC TEE", Role::front, Side::none},
      {"X", "COLLAR RIB", "1XRIB", "", Role::neckband, Side::none},
      {"X", "NECK RIB V", "1XRIB", "", Role::neckband, Side::none},
      {"X", "REGULAR_NECKRIB X", "1X RIB", "", Role::neckband, Side::none},
      {"GMG1016S19-BK", "BACK", "1XFABRIC", "GMG1016S19", Role::back, Side::none},
      {"X", "TM-RIBCOLLAR", "", "", Role::neckband, Side::none},
      {"X", "HALF CO STAND", "2XFABRIC 2XINTERLINI", "", Role::collar_stand, Side::none},
      {"X", "FULL CO UPPER", "1XFABRIC 1X INTERLIN", "", Role::collar, Side::none},
      {"X", "SLEEVE CUFF", "2XRIB", "", Role::cuff, Side::none},
      {"X", "PLACKET INTERLINING", "1XINTERLINING", "", Role::interfacing, Side::none},
      {"X", "PLACKET U_INTERLIN", "1XINTERLINING", "", Role::interfacing, Side::none},
      {"X", "PLACKET LOWER", "1XFABRIC", "", Role::placket, Side::none},
      {"X", "BINDING NECKHOLE", "10X1", "", Role::binding, Side::none},
      {"X", "ARMHOLE BINDING", "10X2", "", Role::binding, Side::none},
      {"X", "TIGHT LEG SHORT", "2X FABRIC", "", Role::leg, Side::none},
      {"ORILEG WB WB", "P1", "RECTANGLE", "ORILEG WB", Role::waistband, Side::none},
      {"COLLARBASEINTERFACE", "", "", "", Role::interfacing, Side::none},
      {"CUFFINTERFACE", "", "", "", Role::interfacing, Side::none},
      {"COLLARBASE", "", "", "", Role::collar_stand, Side::none},
      {"COLLARTOP", "", "", "", Role::collar, Side::none},
      {"POCKETFLAPROUND", "", "", "", Role::pocket_flap, Side::none},
      {"POCKETROUND", "", "", "", Role::pocket, Side::none},
      {"PLACKETUNDER", "", "", "", Role::placket, Side::none},
      {"FRONTPANEL", "", "", "", Role::front, Side::none},
      {"BACKPANEL", "", "", "", Role::back, Side::none},
      {"SHORTSLEEVE", "", "", "", Role::sleeve, Side::none},
      {"YOKE", "", "", "", Role::yoke, Side::none},
      {"FRONT_WITH_POCKET", "", "", "", Role::front, Side::none},
      {"FRONT_NO_POCKET", "", "", "", Role::front, Side::none},
      {"POCKETFRONT", "", "", "", Role::pocket, Side::none},
      {"WAISTBAND1", "", "", "", Role::waistband, Side::none},
      {"DETAIL", "", "", "", Role::unknown, Side::none},
      {"Pattern2D_768516", "", "", "", Role::unknown, Side::none},
  };
  for (const auto& c : cases) expect(c);
}

// The words of Spanish, Portuguese, German, French and Russian files, with
// accents and Cyrillic in any case, and the side a piece is for.
TEST(PieceRole, NamesInOtherLanguages) {
  const Case cases[] = {
      {"Delantero izquierdo", "", "", "", Role::front, Side::left},
      {"Espalda", "", "", "", Role::back, Side::none},
      {"Manga derecha", "", "", "", Role::sleeve, Side::right},
      {"Puño", "", "", "", Role::cuff, Side::none},
      {"Pie de cuello", "", "", "", Role::collar_stand, Side::none},
      {"Canesú", "", "", "", Role::yoke, Side::none},
      {"Bolsillo trasero", "", "", "", Role::pocket, Side::none},
      {"Pretina", "", "", "", Role::waistband, Side::none},
      {"Frente", "", "", "", Role::front, Side::none},
      {"Costas", "", "", "", Role::back, Side::none},
      {"Gola", "", "", "", Role::collar, Side::none},
      {"Punho esquerdo", "", "", "", Role::cuff, Side::left},
      {"Entretela gola", "", "", "", Role::interfacing, Side::none},
      {"Vorderteil", "", "", "", Role::front, Side::none},
      {"Rückenteil", "", "", "", Role::back, Side::none},
      {"Ärmel links", "", "", "", Role::sleeve, Side::left},
      {"Kragensteg", "", "", "", Role::collar_stand, Side::none},
      {"Manschette", "", "", "", Role::cuff, Side::none},
      {"Futter Vorderteil", "", "", "", Role::lining, Side::none},
      {"Bund", "", "", "", Role::waistband, Side::none},
      {"Devant", "", "", "", Role::front, Side::none},
      {"Dos", "", "", "", Role::back, Side::none},
      {"Manche droite", "", "", "", Role::sleeve, Side::right},
      {"Pied de col", "", "", "", Role::collar_stand, Side::none},
      {"Col", "", "", "", Role::collar, Side::none},
      {"Poche", "", "", "", Role::pocket, Side::none},
      {"Полочка", "", "", "", Role::front, Side::none},
      {"Спинка", "", "", "", Role::back, Side::none},
      {"Рукав левый", "", "", "", Role::sleeve, Side::left},
      {"ВОРОТНИК", "", "", "", Role::collar, Side::none},
      {"Стойка воротника", "", "", "", Role::collar_stand, Side::none},
      {"Манжета", "", "", "", Role::cuff, Side::none},
      {"Карман", "", "", "", Role::pocket, Side::none},
      {"Пояс", "", "", "", Role::waistband, Side::none},
      {"Капюшон", "", "", "", Role::hood, Side::none},
      {"Кокетка", "", "", "", Role::yoke, Side::none},
      {"Front left", "", "", "", Role::front, Side::left},
      {"FRONT RT", "", "", "", Role::front, Side::right},
      {"Hood", "", "", "", Role::hood, Side::none},
      {"Belt loop", "", "", "", Role::belt_loop, Side::none},
      {"Fly shield", "", "", "", Role::fly, Side::none},
      {"Care label", "", "", "", Role::label, Side::none},
      {"Back facing", "", "", "", Role::facing, Side::none},
  };
  for (const auto& c : cases) expect(c);
}

// What tells alternatives of one role apart: the name's other words, also
// when they are run together with the role's word.
TEST(PieceRole, VariantWordsTellAlternativesApart) {
  EXPECT_EQ(piece_role("SHORTSLEEVE").variant, std::vector<std::string>{"SHORT"});
  EXPECT_EQ(piece_role("FULLSLEEVE").variant, std::vector<std::string>{"FULL"});
  EXPECT_EQ(piece_role("X", "SLEEVE LONG").variant, (std::vector<std::string>{"X", "LONG"}));
  EXPECT_EQ(piece_role("FRONT_PLEATS").variant, std::vector<std::string>{"PLEATS"});
  EXPECT_TRUE(piece_role("FRONT").variant.empty());
}

// A sleeve's front or back word makes it half of a sleeve cut in two along the
// arm; the name's word wins over the category's (MEN_CLASSIC_TEE's two halves
// carry each other's name as category).
TEST(PieceRole, SleeveHalvesFromTheirFrontOrBackWord) {
  EXPECT_EQ(piece_role("REGULAR TEESL FR", "REGULAR TEESL BK", "2XFABRIC", "MEN CLASSIC TEE").half, Half::front);
  EXPECT_EQ(piece_role("REGULAR TEESL BK", "REGULAR TEESL FR", "2XFABRIC", "MEN CLASSIC TEE").half, Half::back);
  EXPECT_EQ(piece_role("X", "SLEEVE BACK").half, Half::back);
  EXPECT_EQ(piece_role("Manga delantera").half, Half::front);
  EXPECT_EQ(piece_role("SLEEVE").half, Half::none);
  EXPECT_EQ(piece_role("REGULAR TEESL1", "SLEEVE SHORT", "", "MEN CLASSIC TEE").half, Half::none);
  EXPECT_EQ(piece_role("FRONT").half, Half::none) << "only sleeves and legs are cut in halves";
  EXPECT_EQ(piece_role("LEFT SLEEVE FRONT").side, Side::left);
  EXPECT_EQ(half_name(Half::back), "back half");
}

// A trouser word with a front or back word is half a leg; a leg word likewise.
TEST(PieceRole, TrouserLegHalvesFromTheirWords) {
  struct Named {
    const char* name;
    Half half;
  };
  for (const auto& [name, half] : {Named{"TROUSER FRONT", Half::front}, Named{"Pants back", Half::back},
                                   Named{"PANTALON DELANTERO", Half::front}, Named{"Pantalón trasero", Half::back},
                                   Named{"Calça frente", Half::front}, Named{"Vorderhose", Half::front},
                                   Named{"Hinterhose", Half::back}, Named{"Брюки перед", Half::front},
                                   Named{"FRONT LEG", Half::front}, Named{"PANTS", Half::none},
                                   Named{"TIGHT LEG SHORT", Half::none}}) {
    SCOPED_TRACE(name);
    const RoleGuess g = piece_role(name);
    EXPECT_EQ(g.role, Role::leg);
    EXPECT_EQ(g.half, half);
  }
  EXPECT_EQ(piece_role("LEFT TROUSER BACK").side, Side::left);
  EXPECT_EQ(piece_role("TROUSER POCKET").role, Role::pocket);
  EXPECT_EQ(piece_role("TROUSER WAISTBAND").role, Role::waistband);
}

// An annotation makes an interfacing only when interlining is all that is cut.
TEST(PieceRole, AnnotationCountsOnlyForWhatIsCut) {
  EXPECT_EQ(piece_role("P7", "", "1XINTERLINING").role, Role::interfacing);
  EXPECT_EQ(piece_role("P7", "COLLAR", "1XFABRIC 1X INTERLIN").role, Role::collar);
  EXPECT_EQ(piece_role("P7", "", "1XFABRIC").role, Role::unknown);
}

TEST(PieceRole, FoldingKeepsWhatItCannotRead) {
  EXPECT_EQ(fold_name("Puño izquierdo"), "PUNO IZQUIERDO");
  EXPECT_EQ(fold_name("Ärmel"), "ARMEL");
  EXPECT_EQ(fold_name("ёлка"), "ЕЛКА");
  EXPECT_EQ(fold_name(std::string("A\xff"
                                  "b")),
            std::string("A\xff"
                        "B"));                                     // invalid byte kept
  EXPECT_EQ(fold_name(std::string("\xd0")), std::string("\xd0"));  // truncated sequence kept
  EXPECT_FALSE(drapes_as_cloth(Role::interfacing));
  EXPECT_TRUE(drapes_as_cloth(Role::collar));
  EXPECT_TRUE(sewn_on_host(Role::pocket));
  EXPECT_FALSE(sewn_on_host(Role::sleeve));
}
