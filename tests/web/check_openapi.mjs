// Validates docs/api/openapi.yaml with swagger-parser (OpenAPI 3 schema and
// $refs) and prints its operations as JSON, so tests/net/test_openapi.cpp can
// exercise every documented route against the server's answers.
//
//   node check_openapi.mjs FILE
// Output: {"valid": true, "operations": [{"path", "method", "responses": ["200", ...], "websocket"}]}
//     or  {"valid": false, "error": "..."}
import SwaggerParser from '@apidevtools/swagger-parser';

const [file] = process.argv.slice(2);
try {
  const api = await SwaggerParser.validate(file);
  const operations = [];
  for (const [path, item] of Object.entries(api.paths)) {
    for (const method of ['get', 'post', 'put', 'delete', 'patch']) {
      if (!item[method]) continue;
      operations.push({ path, method: method.toUpperCase(), responses: Object.keys(item[method].responses),
        websocket: item[method]['x-websocket'] === true });
    }
  }
  console.log(JSON.stringify({ valid: true, title: api.info.title, operations }));
} catch (e) {
  console.log(JSON.stringify({ valid: false, error: String(e.message || e) }));
}
