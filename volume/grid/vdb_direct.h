#pragma once
/// Reading a float grid straight from an OpenVDB file into our DensityGrid, without OpenVDB.
///
/// OpenVDB itself costs a grid scene more start-up CPU than the render of a small image: binding
/// the module's ~50k relocations, then one heap allocation per leaf node (the whole tree, 31 MB
/// for the 512³ cloud, is first-touched page by page) and one per blosc call, all to be copied
/// into our bricks and freed. This reader maps the file, walks the tree's topology and
/// decompresses each leaf's values into one buffer that feeds DensityGridBuilder directly.
///
/// It reads the layout OpenVDB 3 to 11 write for a float grid (file format 222 to 224: per-grid
/// compression flags, node-mask compression, blosc, zip or no compression, a 5-4-3 tree of
/// leaves and active internal-node tiles, a linear map). Anything else, and every inconsistent
/// or truncated file, is declined, not reported: load_density_grid then reads the file through
/// OpenVDB, which handles the other layouts and names the errors. The layout read (OpenVDB
/// io/Archive.cc, io/GridDescriptor.cc, io/Compression.{h,cc}, tree/RootNode.h,
/// tree/InternalNode.h, tree/LeafNode.h, math/Maps.h; little-endian):
///   header (see vdb_header.h); per grid a descriptor: unique name, type name (suffix
///   "_HalfFloat" when stored as half), instance parent, int64 grid, block and end positions.
///   At the grid position: uint32 compression flags (1 zip, 2 active mask, 4 blosc), the grid's
///   metadata, the transform (map type name, then the map's doubles), int32 buffer count (1),
///   the root (float background, uint32 tile and child counts, tiles as int32 x3, value, bool
///   active; children as int32 x3 origin, then the node), each internal node as child mask,
///   value mask, its values (compressed as below), then its children in offset order; a leaf's
///   topology is its value mask. Then every leaf again in the same order: value mask, values.
///   Values: int8 mask-compression code (0-6), 0-2 inactive values, an optional selection mask,
///   then only the active values (when mask compression is on and the code is not 6) or all of
///   them: blosc or zip as an int64 byte count (negative: raw bytes follow) and the bytes, or raw.
#include "volume/grid/vdb_io.h"

#include <functional>
#include <optional>
#include <string>

namespace kasumi {

/// Reads like load_density_grid (same grid choice, transform, counts and DensityGrid, bit for
/// bit), or returns nullopt with the reason in `why_not` when the file is not one this reader
/// handles or is broken in any way. Throws Error (Input; message starting with `context`, then
/// the path and grid) only for what no reader could load: a transform that is not finite,
/// affine and invertible, active tiles over 2^30 voxels, active voxels spanning more than 2^24
/// per axis or 2^26 bricks (2^35 voxels), a value chunk past the end of the file (also where
/// node masks that claim leaves the file lacks shift the leaves' values, read from where the
/// topology ends as OpenVDB reads them); OpenVDB's path would allocate until it fails there.
/// And a file cut while it is read (another process rewriting it): the mapping's pages past
/// its new end raise SIGBUS, caught for the duration of the read.
std::optional<LoadedGrid> read_density_grid_direct(const std::string& path,
                                                   const std::string& grid_name,
                                                   std::string* why_not = nullptr,
                                                   const std::string& context = std::string());

/// For tests: `hook(path, stage)` runs inside every read while the file is mapped, at stage
/// "topology" (the tree's topology is read) and "values" (the leaves' values are next), so a
/// test can cut the file there as a concurrent writer might. Such a cut is an input error
/// ("the file was cut ... while it was read"), not a crash. Empty: no hook.
void set_direct_read_hook(std::function<void(const std::string& path, const char* stage)> hook);

}  // namespace kasumi
