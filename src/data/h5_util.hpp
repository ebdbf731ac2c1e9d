// h5_util.hpp (internal to the data stage): small wrappers over the HDF5 C++
// API used by the dataset writer and reader. Every failure is a ptnet::Error
// naming the file; HDF5's own error-stack printing is switched off.
#pragma once

#include <H5Cpp.h>

#include <string>

namespace ptnet::h5 {

// Switches off HDF5's automatic error-stack printing (idempotent).
void quiet();

// The innermost descriptions of the current HDF5 error stack, joined by "; "
// (empty when the stack is empty). Used to explain why a file failed to open.
std::string error_stack_text();

// A group without object timestamps (files stay byte-reproducible).
H5::Group create_group(const H5::H5Location& parent, const std::string& name);

// Attributes. Strings are variable-length UTF-8 (h5py reads them as str).
void write_attr(const H5::H5Object& obj, const std::string& name, const std::string& value);
void write_attr(const H5::H5Object& obj, const std::string& name, int value);
void write_attr(const H5::H5Object& obj, const std::string& name, double value);

bool has_attr(const H5::H5Object& obj, const std::string& name);
// Readers throw Error "FILE: WHERE: attribute 'NAME' ..." when absent or of the
// wrong type. `where` names the object ("root group", "sequence 'walk__b1'").
std::string read_string_attr(const H5::H5Object& obj, const std::string& name,
                             const std::string& file, const std::string& where);
double read_number_attr(const H5::H5Object& obj, const std::string& name,
                        const std::string& file, const std::string& where);
long read_integer_attr(const H5::H5Object& obj, const std::string& name,
                       const std::string& file, const std::string& where);

}  // namespace ptnet::h5
