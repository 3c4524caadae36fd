// CRC-32C (Castagnoli: the reflected polynomial 0x82F63B78, RFC 3720 section B.4), the checksum
// TFRecord files frame their records with, and TFRecord's masking of it (algos/training/
// event_file.h writes TensorBoard's event files with them).
#pragma once

#include <cstdint>
#include <string_view>

namespace bsg {

// CRC-32C of `bytes` (crc32c("123456789") = 0xE3069283).
std::uint32_t crc32c(std::string_view bytes);

// TFRecord's masked CRC: ((crc >> 15) | (crc << 17)) + 0xa282ead8, so that a CRC stored inside
// checksummed data does not checksum to a constant.
std::uint32_t masked_crc32c(std::string_view bytes);

}  // namespace bsg
