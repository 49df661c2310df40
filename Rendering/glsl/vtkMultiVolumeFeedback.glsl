// Level-of-detail feedback: the costliest lacking brick of the centre ray of every
// uFeedbackScale-th pixel per axis, one texel each.
layout(r32ui) uniform uimage2D uFeedback;
uniform int uFeedbackScale;
layout(r32f) uniform image2D uFeedbackScore; // the reported brick's cost
bool gFeedbackRay = false;
bool gLackFound = false;
float gLackScore = 0.0;
float gTransmittance = 1.0; // in front of the current step
ivec4 gLack = ivec4(0); // level-0 brick, wanted level
int gLackVolume = 0;
//STRATA::Footprint::Dec
