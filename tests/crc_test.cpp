#include <gtest/gtest.h>

#include "endatsim/protocol/crc.hpp"

using namespace endatsim::protocol;

// Appendix A4.4.2, MakeCrcNorm example: param8 = 13, param16 = 32793 -> 14.
TEST(Crc, MakeCrcNormMatchesTheSpecExample) { EXPECT_EQ(make_crc_norm(13, 32793), 14); }

// Appendix A4.4.2, MakeCrcPos example: 25 clocks, F1 = 0, F2 = 1, EnDat 2.2, 104462 -> 3.
TEST(Crc, MakeCrcPosMatchesTheSpecExample) { EXPECT_EQ(make_crc_pos(25, false, true, true, 104462), 3); }

TEST(Crc, BitSequenceFormEqualsThePositionForm) {
  // F1, F2, then position LSB first: the order on the wire (2.3.1).
  std::vector<std::uint8_t> bits{0, 1};
  for (int i = 0; i < 25; ++i) bits.push_back((104462 >> i) & 1);
  EXPECT_EQ(crc5(bits), 3);
}

TEST(Crc, EnDat21LeavesF2Out) {
  // Worked by hand with the A4 generator: F1 = 0, position 0xA5 in 8 bits -> 11101b.
  EXPECT_EQ(make_crc_pos(8, false, true, false, 0xA5), 0b11101);
  EXPECT_EQ(make_crc_pos(8, false, false, false, 0xA5), 0b11101);  // F2 is "any" with 2.1
}

TEST(Crc, EverySingleBitErrorChangesTheCrc) {
  // A4: "All single errors with data transmission can be detected via the CRC".
  const auto good = make_crc_pos(25, false, true, true, 104462);
  for (int i = 0; i < 25; ++i)
    EXPECT_NE(make_crc_pos(25, false, true, true, 104462 ^ (1 << i)), good) << "bit " << i;
  EXPECT_NE(make_crc_pos(25, true, true, true, 104462), good);
  EXPECT_NE(make_crc_pos(25, false, false, true, 104462), good);
}

TEST(Crc, PresetZeroWithoutInversionReproducesTheMisconfiguredMastersLog) {
  // docs/model.md §12: a published sample's log of 2.1 frames,
  // 25 bits, F1 = 0, where the spec's CRC is 06h, 0Ch, 19h.
  const CrcConfig wrong{0x00, false};
  EXPECT_EQ(make_crc_pos(25, false, true, false, 0xA5A5), 0x06);
  EXPECT_EQ(make_crc_pos(25, false, true, false, 0xA5A5, wrong), 0x05);
  EXPECT_EQ(make_crc_pos(25, false, true, false, 0xA5A6, wrong), 0x0F);
  EXPECT_EQ(make_crc_pos(25, false, true, false, 0xA5A7, wrong), 0x1A);
  EXPECT_EQ(make_crc_pos(25, false, true, false, 0xA5A5, CrcConfig{}), 0x06) << "the default is the spec's";
}

TEST(Crc, NotesVectorsForOtherWidths) {
  // docs/model.md §12 (a published master's make_crc_* and an independent LFSR agree).
  EXPECT_EQ(make_crc_pos(31, false, false, true, 0x7FFFFFFF), 22);
  EXPECT_EQ(make_crc_pos(36, false, false, true, 0x512345678ULL), 13);
  EXPECT_EQ(make_crc_pos(48, false, false, true, 0xABCD12345678ULL), 11);
  EXPECT_EQ(make_crc_norm(0xB9, 0x1234), 10);
  EXPECT_EQ(make_crc_norm(100, 10000), 30);
}
