/* text_file.h - reading a whole (small) text file, for the tools' JSON inputs. */
#ifndef CACAO_TEXT_FILE_H
#define CACAO_TEXT_FILE_H

#include <stddef.h>

/* The file's bytes, zero-terminated (caller frees), or NULL with a message naming the file in err
 * (cannot open, read error, larger than max_bytes, out of memory). */
char *cacao_read_text_file(const char *path, size_t max_bytes, char *err, size_t err_size);

#endif /* CACAO_TEXT_FILE_H */
