//! Microfacet BRDFs (in progress).
