//! Cutting a closed triangle mesh by planes into cross-sections (to be written).
