// Replaced by the renderer (issue 3); keeps the target non-empty until then.
namespace drape::render {
int rendererPlaceholder() { return 0; }
}  // namespace drape::render
