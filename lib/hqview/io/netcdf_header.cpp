#include "hqview/io/netcdf_header.h"

#include <algorithm>
#include <limits>
#include <vector>

#include "hqview/core/error.h"
#include "hqview/io/text_scanner.h"

namespace hq::detail {
namespace {

// List tags of the header (the spec's NC_DIMENSION, NC_VARIABLE, NC_ATTRIBUTE).
constexpr std::uint32_t kDimensionTag = 0x0A;
constexpr std::uint32_t kVariableTag = 0x0B;
constexpr std::uint32_t kAttributeTag = 0x0C;
constexpr std::uint64_t kMaxNameLength = 256;  // NC_MAX_NAME
constexpr std::uint64_t kSaturated = std::numeric_limits<std::uint64_t>::max();

std::uint64_t saturating_mul(std::uint64_t a, std::uint64_t b) {
  if (a != 0 && b > kSaturated / a) return kSaturated;
  return a * b;
}
std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) { return b > kSaturated - a ? kSaturated : a + b; }
std::uint64_t padded4(std::uint64_t n) { return n > kSaturated - 3 ? kSaturated : (n + 3) / 4 * 4; }

// Bytes of one value of an nc_type (NC_BYTE = 1 ... NC_UINT64 = 11); 0 for
// a type this file version does not have.
std::uint64_t type_size(std::uint32_t type, int version) {
  constexpr std::uint64_t kSizes[] = {0, 1, 1, 2, 4, 4, 8, 1, 2, 4, 8, 8};
  const std::uint32_t last = version == 5 ? 11 : 6;
  return type >= 1 && type <= last ? kSizes[type] : 0;
}

struct Dimension {
  std::string name;
  std::uint64_t length = 0;  // 0: the record dimension
};

class HeaderWalk {
 public:
  HeaderWalk(std::string_view bytes, const std::string& name)
      : bytes_(bytes), name_(name), version_(static_cast<unsigned char>(bytes[3])) {}

  std::uint64_t run() {
    pos_ = 4;
    std::uint64_t numrecs = version_ == 5 ? read_u64("the number of records") : read_u32("the number of records");
    const bool is_streaming = numrecs == (version_ == 5 ? kSaturated : 0xFFFFFFFFu);
    if (is_streaming) numrecs = 0;  // netCDF counts the records from the file size
    read_dimensions();
    read_attributes("global attribute");
    read_variables(numrecs);
    return pos_;
  }

 private:
  std::uint64_t size() const { return bytes_.size(); }

  [[noreturn]] void claims(std::uint64_t needed, const std::string& what) const {
    throw ParseError(name_, 0,
                     "exodus header claims " +
                         (needed == kSaturated ? std::string("2^64 or more") : std::to_string(needed)) +
                         " bytes for " + what + " but the file has " + std::to_string(size()));
  }
  [[noreturn]] void malformed(const std::string& what) const {
    throw ParseError(name_, 0, "not an Exodus II (netCDF) file: " + what);
  }

  // n more header bytes must follow the current position.
  void need(std::uint64_t n, const std::string& what) const {
    if (n > size() - pos_) claims(saturating_add(pos_, n), what);
  }

  std::uint32_t read_u32(const std::string& what) {
    need(4, what);
    std::uint32_t value = 0;
    for (int i = 0; i < 4; ++i) value = value << 8 | static_cast<unsigned char>(bytes_[pos_ + i]);
    pos_ += 4;
    return value;
  }
  std::uint64_t read_u64(const std::string& what) {
    need(8, what);
    std::uint64_t value = 0;
    for (int i = 0; i < 8; ++i) value = value << 8 | static_cast<unsigned char>(bytes_[pos_ + i]);
    pos_ += 8;
    return value;
  }
  // The spec's NON_NEG: 32 bits in CDF-1 and CDF-2, 64 bits in CDF-5.
  std::uint64_t read_count(const std::string& what) { return version_ == 5 ? read_u64(what) : read_u32(what); }
  // The spec's OFFSET: 32 bits in CDF-1, 64 bits in CDF-2 and CDF-5.
  std::uint64_t read_offset(const std::string& what) { return version_ == 1 ? read_u32(what) : read_u64(what); }

  std::string read_name(const std::string& what) {
    const std::uint64_t length = read_count("the name of " + what);
    need(padded4(length), "the name of " + what);
    if (length == 0 || length > kMaxNameLength)
      malformed("the name of " + what + " has " + std::to_string(length) + " bytes (expected 1 to 256)");
    // Quoted, with control and non-ASCII bytes escaped: it goes into messages.
    std::string text = quote(bytes_.substr(pos_, length));
    pos_ += padded4(length);
    return text;
  }

  // A list's tag and element count: ABSENT (two zeros) or tag, nelems. Each
  // element takes at least min_entry bytes.
  std::uint64_t read_list(std::uint32_t tag, std::uint64_t min_entry, const std::string& plural) {
    const std::uint64_t start = pos_;
    const std::uint32_t found = read_u32("the list of " + plural);
    const std::uint64_t count = read_count("the number of " + plural);
    if (found == 0 && count == 0) return 0;
    if (found != tag) malformed("expected the list of " + plural + " at byte " + std::to_string(start));
    need(saturating_mul(count, min_entry), std::to_string(count) + " " + plural);
    return count;
  }

  // The smallest entries: a 1-byte name (4 bytes padded) after its length.
  std::uint64_t count_bytes() const { return version_ == 5 ? 8 : 4; }
  std::uint64_t min_name() const { return count_bytes() + 4; }

  void read_dimensions() {
    const std::uint64_t count = read_list(kDimensionTag, min_name() + count_bytes(), "dimensions");
    dimensions_.reserve(static_cast<std::size_t>(count));
    for (std::uint64_t i = 0; i < count; ++i) {
      Dimension dim;
      dim.name = read_name("dimension " + std::to_string(i));
      dim.length = read_count("the length of dimension " + dim.name);
      if (dim.length == 0) {
        if (record_dimension_ >= 0) malformed("a second record dimension, " + dim.name);
        record_dimension_ = static_cast<std::int64_t>(i);
      } else if (dim.length > size()) {
        // Every value of a variable takes at least one byte.
        claims(dim.length, "dimension " + dim.name + " of length " + std::to_string(dim.length));
      }
      dimensions_.push_back(std::move(dim));
    }
  }

  void read_attributes(const std::string& what) {
    const std::uint64_t count = read_list(kAttributeTag, min_name() + 4 + count_bytes(), what + "s");
    for (std::uint64_t i = 0; i < count; ++i) {
      const std::string attribute = what + " " + read_name(what + " " + std::to_string(i));
      const std::uint32_t type = read_u32("the type of " + attribute);
      const std::uint64_t bytes_per_value = type_size(type, version_);
      if (bytes_per_value == 0) malformed("unknown type " + std::to_string(type) + " of " + attribute);
      const std::uint64_t values = read_count("the length of " + attribute);
      const std::uint64_t bytes = padded4(saturating_mul(values, bytes_per_value));
      need(bytes, attribute + " (" + std::to_string(values) + " values)");
      pos_ += bytes;
    }
  }

  void read_variables(std::uint64_t numrecs) {
    const std::uint64_t min_variable =
        min_name() + count_bytes() + 4 + count_bytes() + 4 + count_bytes() + (version_ == 1 ? 4 : 8);
    const std::uint64_t count = read_list(kVariableTag, min_variable, "variables");
    std::uint64_t fixed_total = 0;
    std::vector<std::uint64_t> record_slabs;
    std::uint64_t first_record_begin = kSaturated, first_record_slab = 0;
    for (std::uint64_t i = 0; i < count; ++i) {
      const std::string variable = "variable " + read_name("variable " + std::to_string(i));
      const std::uint64_t num_dims = read_count("the dimensions of " + variable);
      need(saturating_mul(num_dims, count_bytes()), std::to_string(num_dims) + " dimensions of " + variable);
      std::uint64_t values = 1;
      bool is_record = false;
      for (std::uint64_t j = 0; j < num_dims; ++j) {
        const std::uint64_t id = read_count("the dimensions of " + variable);
        if (id >= dimensions_.size())
          malformed(variable + " uses dimension id " + std::to_string(id) + " of " +
                    std::to_string(dimensions_.size()));
        if (static_cast<std::int64_t>(id) == record_dimension_) {
          if (j != 0) malformed(variable + " uses the record dimension after its first dimension");
          is_record = true;
        } else {
          values = saturating_mul(values, dimensions_[id].length);
        }
      }
      read_attributes(variable + " attribute");
      const std::uint32_t type = read_u32("the type of " + variable);
      const std::uint64_t bytes_per_value = type_size(type, version_);
      if (bytes_per_value == 0) malformed("unknown type " + std::to_string(type) + " of " + variable);
      read_count("the size of " + variable);  // vsize: redundant, and wrong for > 4 GiB variables
      const std::uint64_t begin = read_offset("the offset of " + variable);
      const std::uint64_t bytes = saturating_mul(values, bytes_per_value);
      if (is_record) {
        if (begin > size()) claims(begin, variable + " (its first record's offset)");
        record_slabs.push_back(bytes);
        if (begin < first_record_begin) {
          first_record_begin = begin;
          first_record_slab = bytes;
        }
      } else {
        const std::uint64_t end = saturating_add(begin, bytes);
        if (end > size())
          claims(end, variable + " (" + std::to_string(bytes) + " bytes at offset " + std::to_string(begin) + ")");
        fixed_total = saturating_add(fixed_total, bytes);
      }
    }
    if (fixed_total > size()) claims(fixed_total, "its " + std::to_string(count) + " fixed-size variables");
    // One record holds a slab of every record variable, each padded to 4
    // bytes unless there is only one.
    std::uint64_t recsize = 0;
    for (const std::uint64_t slab : record_slabs)
      recsize = saturating_add(recsize, record_slabs.size() == 1 ? slab : padded4(slab));
    // The records start at the first record variable; the last one must hold
    // at least that variable (writers without fill may leave the others out).
    if (numrecs == 0 || record_slabs.empty()) return;
    const std::uint64_t records = saturating_mul(numrecs, recsize);
    const std::uint64_t end =
        saturating_add(first_record_begin, saturating_add(saturating_mul(numrecs - 1, recsize), first_record_slab));
    if (records > size() || end > size())
      claims(std::max(records, end), std::to_string(numrecs) + " records of " + std::to_string(recsize) +
                                         " bytes from offset " + std::to_string(first_record_begin));
  }

  std::string_view bytes_;
  const std::string& name_;
  int version_;
  std::uint64_t pos_ = 0;
  std::vector<Dimension> dimensions_;
  std::int64_t record_dimension_ = -1;
};

}  // namespace

bool is_netcdf_classic(std::string_view bytes) {
  return bytes.size() >= 4 && bytes.starts_with("CDF") && (bytes[3] == 1 || bytes[3] == 2 || bytes[3] == 5);
}

std::uint64_t check_netcdf_classic_header(std::string_view bytes, const std::string& name) {
  if (!is_netcdf_classic(bytes)) throw ParseError(name, 0, "not an Exodus II (netCDF) file: no CDF signature");
  return HeaderWalk(bytes, name).run();
}

}  // namespace hq::detail
