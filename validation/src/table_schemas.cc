#include "crankcheck/validation/table_schemas.h"

#include "crankcheck/validation/campaign.h"
#include "crankcheck/validation/grade.h"
#include "crankcheck/validation/parts.h"

namespace crankcheck::validation {

const TableSchema* findTableSchema(const std::string& name) {
  if (name == kNotesTable.name()) return &kNotesTable;
  if (const TableSchema* schema = findGradeTableSchema(name)) return schema;
  for (const Part* part : listParts())
    for (const TableSchema* schema : part->schemas())
      if (schema->name() == name) return schema;
  return nullptr;
}

}  // namespace crankcheck::validation
