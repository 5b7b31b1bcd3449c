/* viscolube (private): the material database below its public part
 * (viscolube/database.h), for tests: the schema version. The private parts
 * the files of src/db/ share are in db_internal.h. */
#ifndef VISCOLUBE_DATABASE_INTERNAL_H
#define VISCOLUBE_DATABASE_INTERNAL_H

/* The schema version this program creates and understands. */
int vl_db_schema_version(void);

#endif
