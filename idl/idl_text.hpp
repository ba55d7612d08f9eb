#pragma once
// The text of idl/maptr.idl, compiled in: the schema that recordings carry (MCAP "omgidl").

namespace maptr::msg {

/// The whole IDL file, as in the source tree when the build was configured.
const char* idl_text();

}  // namespace maptr::msg
