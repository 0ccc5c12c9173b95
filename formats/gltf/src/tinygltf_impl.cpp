// Placeholder until the format lands; returns an error so callers see it is missing.
// tinygltf compiled here with Draco enabled (see third_party_notes/tinygltf.md).
