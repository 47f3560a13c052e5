// The record structure of an ECLIPSE binary file, checked before opm-common's EclIO reads it.
#pragma once
#include <string>

namespace ugs::eclipse {

// True when EclIO reads `path` as a formatted (text) file: the first letter of its extension is one
// of A B C F G H (opm-common's isFormatted: CASE.FEGRID, CASE.FUNRST, CASE.F0001, ...).
bool is_formatted(const std::string& path);

// Checks the structure of an ECLIPSE output file before EclIO reads it, and throws an InputError
// naming the byte and the array where the file goes wrong. EclIO trusts every item count it reads:
// a count too large makes it allocate that many items (a formatted file's count of 2^31 fills 23 GB
// of memory), a record marker off sends its next read into the data.
//   - Binary: Fortran records (a big-endian int32 byte count, the bytes, the same count again); an
//     array is a 16-byte header record (name, item count, type) and its items in records of at most
//     1000 numbers or 105 strings. Every marker and count is checked, to the end of the file.
//   - Formatted: a header line ('NAME' count 'TYPE') and the items in lines of a fixed width; EclIO
//     finds the next header by the size the count implies: each size must fit in the file.
void check_records(const std::string& path);

}  // namespace ugs::eclipse
