#!/usr/bin/python3
"""Writes the HDF5 fixtures of this folder (README): small ptnet datasets
(a 4 x 2 mat, 3 frames) one of whose objects reaches outside the file, or
points elsewhere inside it. Run with Debian's python3-h5py:

    cd tests/data/hdf5_links && /usr/bin/python3 make_fixtures.py

The targets named in the links (target.h5, raw.f32, source.h5) are not
kept here: a test creates them (or a FIFO of that name) beside a copy of
the fixture, to see that the reader never opens them."""
import h5py
import numpy as np

ROWS, COLS, FRAMES = 4, 2, 3


def dataset(path):
    f = h5py.File(path, "w", track_order=False)
    f.attrs.create("format", "ptnet-dataset", dtype=h5py.string_dtype())
    f.attrs["version"] = np.int32(1)
    f.attrs["fps"] = 30.0
    f.attrs["rows"] = np.int32(ROWS)
    f.attrs["cols"] = np.int32(COLS)
    f.attrs["pitch_m"] = 0.02
    f.attrs.create("units", "kPa", dtype=h5py.string_dtype())
    bodies = np.array([(b"b1", 0, 160.0, 55.0, b"original"), (b"b2", 1, 180.0, 80.0, b"original")],
                      dtype=[("id", "S2"), ("sex", "i1"), ("height_cm", "f8"), ("weight_kg", "f8"),
                             ("role", "S8")])
    f["bodies"] = bodies
    f.create_group("sequences")
    sequence(f, "walk__b1", "b1")
    return f


def sequence(f, name, body, **kwargs):
    if kwargs:
        ds = f["sequences"].create_dataset(name, shape=(FRAMES, ROWS, COLS), dtype="<f4", **kwargs)
    else:
        ds = f["sequences"].create_dataset(name, data=np.ones((FRAMES, ROWS, COLS), "<f4"))
    for key, value in (("body_id", body), ("motion_id", "walk"), ("category", "walking")):
        ds.attrs.create(key, value, dtype=h5py.string_dtype())
    ds.attrs["take"] = np.int32(1)
    return ds


# A sequence that is an external link: to another file's sequence.
with dataset("external_link.h5") as f:
    f["sequences/walk__b2"] = h5py.ExternalLink("target.h5", "/sequences/walk__b1")

# The /sequences group itself an external link (the reader resolves it first).
with dataset("external_group.h5") as f:
    del f["sequences"]
    f["sequences"] = h5py.ExternalLink("target.h5", "/sequences")

# A soft link: the same sequence again under another name.
with dataset("soft_link.h5") as f:
    f["sequences/walk__b2"] = h5py.SoftLink("/sequences/walk__b1")

# /bodies a soft link to a table elsewhere in the file.
with dataset("soft_bodies.h5") as f:
    f.move("bodies", "table")
    f["bodies"] = h5py.SoftLink("/table")

# A sequence whose frames are stored in a raw file outside (external storage).
with dataset("external_storage.h5") as f:
    sequence(f, "walk__b2", "b2", external=[("raw.f32", 0, FRAMES * ROWS * COLS * 4)])

# A virtual dataset: a sequence mapped from another file's dataset.
with dataset("virtual.h5") as f:
    layout = h5py.VirtualLayout(shape=(FRAMES, ROWS, COLS), dtype="<f4")
    layout[:] = h5py.VirtualSource("source.h5", "/frames", shape=(FRAMES, ROWS, COLS))
    ds = f["sequences"].create_virtual_dataset("walk__b2", layout, fillvalue=0)
    for key, value in (("body_id", "b2"), ("motion_id", "walk"), ("category", "walking")):
        ds.attrs.create(key, value, dtype=h5py.string_dtype())
    ds.attrs["take"] = np.int32(1)

# An external link in a group the reader does not read (every link counts).
with dataset("external_elsewhere.h5") as f:
    f["notes"] = h5py.ExternalLink("target.h5", "/")

# A virtual dataset of unlimited extent: its size is its sources' (HDF5
# would open them to learn it).
with dataset("virtual_unlimited.h5") as f:
    layout = h5py.VirtualLayout(shape=(FRAMES, ROWS, COLS), dtype="<f4", maxshape=(None, ROWS, COLS))
    source = h5py.VirtualSource("source.h5", "/frames", shape=(FRAMES, ROWS, COLS), maxshape=(None, ROWS, COLS))
    layout[0:h5py.h5s.UNLIMITED, :, :] = source[0:h5py.h5s.UNLIMITED, :, :]
    ds = f["sequences"].create_virtual_dataset("walk__b2", layout, fillvalue=0)
    for key, value in (("body_id", "b2"), ("motion_id", "walk"), ("category", "walking")):
        ds.attrs.create(key, value, dtype=h5py.string_dtype())
    ds.attrs["take"] = np.int32(1)

# A second hard link to a sequence: one object under two names.
with dataset("hard_link_twice.h5") as f:
    f["sequences/walk__b2"] = f["sequences/walk__b1"]

# The same writer's dataset without links: it opens.
with dataset("good.h5") as f:
    pass

# A group linked back to the root: the whole file under a second name.
with dataset("hard_link_loop.h5") as f:
    f["sequences/all"] = f["/"]
