// Level-of-detail feedback (paged horizons): one pixel per uFeedbackScale^2 lattice cell asks
// for the tile its hit lies in, at the level whose cells cover about uLodScale pixels' worth of
// the pixel's footprint; the lattice phase uFeedbackOffset cycles over the frames.
layout(r32ui) uniform uimage2D uFeedback;
uniform int uFeedbackScale;
uniform ivec2 uFeedbackOffset;
uniform float uLodScale;
uniform int uPageLevels;
uniform int uLevelTilesX[32];
