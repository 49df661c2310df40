uniform usampler3D uSkip@n@;
uniform vec4 uSkipGrid@n@; // cells per axis, cell size in voxels
