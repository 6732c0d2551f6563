// Typed errors of the LiftRemesh core. Every message says what was wrong and what was expected.
#pragma once

#include <stdexcept>
#include <string>

namespace liftremesh {

//! Base of every error the core throws.
class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

//! The caller gave something unusable: a bad file, a bad array, a parameter out of range.
class InvalidInput : public Error {
public:
    using Error::Error;
};

//! The computation produced a non-finite value or could not proceed numerically.
class NumericalFailure : public Error {
public:
    using Error::Error;
};

//! The output could not be made a valid surface (e.g. no restricted Delaunay triangle at all).
class TopologyFailure : public Error {
public:
    using Error::Error;
};

//! The progress callback asked to stop. Nothing half-made is returned.
class Cancelled : public Error {
public:
    using Error::Error;
};

} // namespace liftremesh
