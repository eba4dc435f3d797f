//! Small writers of optical profiler formats (AL3D, FRT, BCR, TMD, VK4,
//! PLUX, ZON), after their public descriptions: the fixtures of the
//! round-trip and variant tests.
