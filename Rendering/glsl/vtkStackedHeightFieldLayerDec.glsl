// One peel of strata::VolumeSurfaceLayers: the opaque scene's window depth and layer k - 1's (for
// k > 0), per pixel of the peel's viewport-sized framebuffer.
uniform sampler2D uPeelScene;
uniform sampler2D uPeelPrevious;
uniform int uPeelLayer;
