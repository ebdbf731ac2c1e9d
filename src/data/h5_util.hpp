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

// What a ptnet dataset may not hold: objects outside the file. Throws Error
// "FILE: /sequences/x is an external link to 'other.h5:/y'; ..." at the first
// link of the file (every group reached through hard links) that is not a
// hard link: an external link (HDF5 would open another file, even a FIFO
// that never answers), a soft or user-defined link (another object of the
// file, or of none, under a second name), or a second hard link to an
// object (a sequence twice). Nothing is traversed or opened.
void check_hard_links(const H5::H5File& file, const std::string& path);
// Throws Error "FILE: WHERE is a virtual dataset ..." or "... keeps its data
// in the external file 'raw.f32' ..." for a dataset whose data HDF5 would
// read from other files. Call it on a dataset just opened, before anything
// else: a virtual dataset's size may be read from its source files.
void check_local_storage(const H5::DataSet& ds, const std::string& path, const std::string& where);

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
