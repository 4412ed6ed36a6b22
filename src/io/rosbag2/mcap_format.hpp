#pragma once
// Constants of the MCAP container format (mcap.dev/spec, major version 0),
// shared by our reader and the test writer.
//
//   <magic><Header><data section records...><DataEnd>[summary records...]<Footer><magic>
//
// Every record is <opcode u8><content length u64><content>, little endian.
// Strings and byte arrays carry a u32 length (Chunk records and Attachment
// data a u64 one); maps a u32 byte length. The data section CRC32 covers
// every byte from the start of the file up to the DataEnd record; a Chunk's
// CRC32 covers its uncompressed records. A CRC of 0 means "not computed".
#include <cstdint>

namespace dsswarm::mcap {

inline constexpr std::uint8_t kMagic[8] = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

enum class Op : std::uint8_t {
  Header = 0x01,
  Footer = 0x02,
  Schema = 0x03,
  Channel = 0x04,
  Message = 0x05,
  Chunk = 0x06,
  MessageIndex = 0x07,
  ChunkIndex = 0x08,
  Attachment = 0x09,
  AttachmentIndex = 0x0A,
  Statistics = 0x0B,
  Metadata = 0x0C,
  MetadataIndex = 0x0D,
  SummaryOffset = 0x0E,
  DataEnd = 0x0F,
};

inline constexpr std::size_t kRecordPrefixBytes = 1 + 8;  // opcode, content length

// Chunk compressions (an empty string: none). lz4 is the LZ4 *frame* format.
inline constexpr const char* kZstd = "zstd";
inline constexpr const char* kLz4 = "lz4";

}  // namespace dsswarm::mcap
