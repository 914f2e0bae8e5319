#pragma once
// The physics a result was made with. It counts the releases whose physics moved shipped
// results (CHANGELOG.md names each, with what it did to every shipped verdict), so a reader
// holding two result files can tell whether they come from the same model before comparing
// them. Raise it, and describe the change in CHANGELOG.md, whenever the physics changes a
// result; an output-only change leaves it.
namespace j232::assess {

inline constexpr int kModelVersion = 8;
inline constexpr const char* kModelPhysics =
    "rigid-rod nail (capsule) struck by the impulse-momentum blade of report 445-1 generalised; the capsule against the scene's "
    "real faces, found conservatively; Stronge's energetic restitution with Coulomb friction integrated along the normal "
    "impulse; contacts resolved one at a time, gentle ones (slower than sqrt(2 g D)) counted apart from bounces and wedges named; a field's objects held up "
    "by supports of exponential height, bounced on the turf in its frame, skidding along the mower's steel unless round";

}  // namespace j232::assess
