// Replaced by the desktop application (issue 7); keeps the target non-empty until then.
namespace drape::qt {
int qtPlaceholder() { return 0; }
}  // namespace drape::qt
