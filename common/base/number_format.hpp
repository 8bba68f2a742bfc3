#pragma once
// Numbers in messages: what a refusal asked for and what it would take, read by a person.
#include <string>

namespace physarum {

// printf-style formatting of one number with %g (never "0.000000" for a small bound).
std::string format_number(double value);
// Bytes with a binary unit: "1.5 GiB".
std::string format_bytes(double bytes);

}  // namespace physarum
